#pragma once
// Topology dilation through OpenVDB's morphology, threaded only where it
// pays. Its threaded path has a cost of its own that the serial one has
// not: on 2 cores, a sphere shell of 645 leaves dilates by one voxel
// (face neighbours) in 1 ms serially and 9-19 ms threaded, one of 9,033
// leaves in 9.5-9.9 ms against 13.4-13.9 ms, while one of 64,800 leaves
// takes 70 ms serially and 41 ms threaded (docs/measurements.md, Topology
// dilation); on one thread the threaded path is slower at every size.
// The result is the same either way.
#include <openvdb/tools/Morphology.h>
#include <tbb/global_control.h>

#include <cstddef>

namespace weft {

constexpr std::size_t kThreadedDilationLeaves = 16384;

// openvdb::tools::dilateActiveValues on a tree or a LeafManager, threaded
// from kThreadedDilationLeaves leaves on when more than one thread may run.
template <class TreeOrLeafManager>
void dilateTopology(TreeOrLeafManager& tree, int iterations, openvdb::tools::NearestNeighbors neighbours,
                    openvdb::tools::TilePolicy tiles) {
    const bool threaded = std::size_t(tree.leafCount()) >= kThreadedDilationLeaves &&
                          tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1;
    openvdb::tools::dilateActiveValues(tree, iterations, neighbours, tiles, threaded);
}

}  // namespace weft
