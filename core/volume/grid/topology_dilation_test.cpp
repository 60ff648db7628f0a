// dilateTopology gives OpenVDB's dilation whichever path it takes: below
// kThreadedDilationLeaves leaves (serial) and above (threaded), with face
// and 26-neighbourhoods, tiles expanded, the same active voxels as the
// other path.
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <cmath>

#include "core/base/rng.hpp"
#include "core/volume/grid/topology_dilation.hpp"

namespace weft {
namespace {

// Scattered voxels in about `leaves` leaves, and one active tile.
openvdb::MaskTree scattered(int leaves, std::uint64_t seed) {
    openvdb::MaskTree tree(false);
    Rng rng(seed);
    const int side = int(std::cbrt(double(leaves))) + 1;
    for (int i = 0; i < leaves; ++i) {
        const openvdb::Coord leaf(8 * (i % side), 8 * ((i / side) % side), 8 * (i / (side * side)));
        for (int k = 0; k < 3; ++k)
            tree.setValueOn(leaf + openvdb::Coord(int(rng.uniform() * 8), int(rng.uniform() * 8), int(rng.uniform() * 8)));
    }
    tree.addTile(1, openvdb::Coord(-128, 0, 0), true, true);  // a 128^3 tile beside the voxels
    return tree;
}

void expectSameAsOtherPath(int leaves, openvdb::tools::NearestNeighbors neighbours) {
    openvdb::MaskTree mine = scattered(leaves, 3), theirs = scattered(leaves, 3);
    const bool threaded = std::size_t(mine.leafCount()) >= kThreadedDilationLeaves;
    dilateTopology(mine, 2, neighbours, openvdb::tools::EXPAND_TILES);
    openvdb::tools::dilateActiveValues(theirs, 2, neighbours, openvdb::tools::EXPAND_TILES, /*threaded=*/!threaded);
    EXPECT_GT(mine.activeVoxelCount(), scattered(leaves, 3).activeVoxelCount());
    EXPECT_EQ(mine.activeVoxelCount(), theirs.activeVoxelCount());
    openvdb::MaskTree difference = mine;
    difference.topologyDifference(theirs);
    EXPECT_EQ(difference.activeVoxelCount(), 0u);
    theirs.topologyDifference(mine);
    EXPECT_EQ(theirs.activeVoxelCount(), 0u);
}

TEST(TopologyDilation, SmallTreesMatchTheThreadedDilation) {
    expectSameAsOtherPath(500, openvdb::tools::NN_FACE);
    expectSameAsOtherPath(500, openvdb::tools::NN_FACE_EDGE_VERTEX);
}

TEST(TopologyDilation, LargeTreesMatchTheSerialDilation) {
    const int leaves = int(kThreadedDilationLeaves) + 500;
    expectSameAsOtherPath(leaves, openvdb::tools::NN_FACE);
}

}  // namespace
}  // namespace weft
