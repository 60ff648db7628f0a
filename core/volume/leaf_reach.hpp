#pragma once
// The voxels within a few voxels (Chebyshev distance: a cube) of a mask's
// active voxels, worked leaf by leaf and in parallel. Each 8^3 leaf reads
// the mask `reach` voxels beyond it on every side as a block of bits, each
// (x, y) one 64-bit word of its voxels along z; growing the block by one
// voxel in x, y and z is a few shifts and ORs per word, and a leaf voxel
// first set after k growths is k voxels from the mask. The oracles'
// distance fields and the light caches' topology are made this way instead
// of with OpenVDB's dilation, whose passes over the whole tree run mostly
// on one thread.
#include <openvdb/openvdb.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace weft {

constexpr int kMaxLeafReach = 16;  // a block of 8 + 2 * 16 = 40 bits per word

class LeafDistances {
public:
    explicit LeafDistances(int reach);  // reach in [0, kMaxLeafReach]

    // Distances (reach + 1 where farther) from the active voxels of `mask`
    // (no active tiles: voxelize them first) to the 512 voxels of the leaf at
    // `origin`, in the leaf's offset order; null when none is within reach.
    const std::uint8_t* of(const openvdb::MaskTree& mask, const openvdb::Coord& origin);

private:
    std::uint64_t& row(int x, int y) { return rows_[std::size_t(x) * B_ + y]; }
    bool load(const openvdb::MaskTree& mask, const openvdb::Coord& lo);
    void grow(int k);
    int record(int k);

    int K_, B_;
    std::uint64_t inBlock_;
    std::vector<std::uint64_t> rows_, grown_;
    std::uint8_t done_[64];
    std::uint8_t out_[512];
};

// Origins of the leaves with a voxel within `reach` of a leaf of `mask`, sorted.
std::vector<openvdb::Coord> leafOriginsNear(const openvdb::MaskTree& mask, int reach);

// make(origin, distances) for every leaf with a voxel within `reach` of the
// mask, in parallel; the leaves it returns (a std::unique_ptr to one of
// tree's leaves, or null) are then added to `tree`.
template <class Tree, class Make>
void addLeavesNear(Tree& tree, const openvdb::MaskTree& mask, int reach, const Make& make) {
    using Leaf = typename Tree::LeafNodeType;
    const std::vector<openvdb::Coord> origins = leafOriginsNear(mask, reach);
    std::vector<std::unique_ptr<Leaf>> leaves(origins.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, origins.size(), 16), [&](const tbb::blocked_range<std::size_t>& r) {
        LeafDistances distances(reach);
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            if (const std::uint8_t* d = distances.of(mask, origins[i])) leaves[i] = make(origins[i], d);
    });
    for (auto& leaf : leaves)
        if (leaf) tree.addLeaf(leaf.release());
}

}  // namespace weft
