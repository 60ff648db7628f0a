#pragma once
// The voxels within a few voxels (Chebyshev distance: a cube) of a mask's
// active voxels, worked a column of leaves at a time and in parallel. A
// column is up to a few 8^3 leaves stacked along z; it reads the mask
// `reach` voxels beyond it on every side as a block of bits, each (x, y)
// one 64-bit word of its voxels along z; growing the block by one voxel in
// x, y and z is a few shifts and ORs per word, and a voxel first set after
// k growths is k voxels from the mask. Stacking leaves in the words shares
// the growth of the block's x and y apron among them: one leaf alone used
// 22 of a word's 64 bits at reach 7, six leaves use 62. The oracles'
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

    // Leaves a column can stack: 8 voxels each and `reach` on both ends in 64 bits.
    static int columnLeaves(int reach) { return (64 - 2 * reach) / 8; }

    // Distances (reach + 1 where farther) from the active voxels of `mask`
    // (no active tiles: voxelize them first) to the voxels of the `count`
    // leaves (1 .. columnLeaves()) at origin, origin + (0, 0, 8), ...; then
    // leaf(s) gives the 512 of leaf s in the leaf's offset order, null when
    // none is within reach, and within(s) the voxels within reach as a
    // leaf's value mask (8 words; bit 64 x + 8 y + z). They last until the
    // next call.
    void column(const openvdb::MaskTree& mask, const openvdb::Coord& origin, int count);
    const std::uint8_t* leaf(int s) const { return found_[std::size_t(s)] ? out_.data() + 512 * std::size_t(s) : nullptr; }
    const std::uint64_t* within(int s) const { return within_.data() + 8 * std::size_t(s); }

private:
    std::uint64_t& row(int x, int y) { return rows_[std::size_t(x) * B_ + y]; }
    bool load(const openvdb::MaskTree& mask, const openvdb::Coord& lo, int depth);
    void grow(int k);
    bool record();
    void finish();

    int K_, B_, S_, P_, n_ = 0;
    std::uint64_t inBlock_;
    std::vector<std::uint64_t> rows_, grown_;
    // Per (x, y) of the leaves, their 8 n voxels along z: the growth steps
    // so far that missed each, a binary count with bit p in planes_[p];
    // and which the last step reached.
    std::vector<std::uint64_t> planes_, reached_;
    std::vector<std::uint64_t> within_;  // 8 per leaf of the column
    std::vector<std::uint8_t> out_;      // 512 per leaf of the column
    std::vector<std::uint16_t> found_;   // voxels within reach, per leaf
};

// Origins of the leaves with a voxel within `reach` of a leaf of `mask`, sorted.
std::vector<openvdb::Coord> leafOriginsNear(const openvdb::MaskTree& mask, int reach);

// Runs of the sorted `origins` that one LeafDistances column holds: leaves
// of the same x and y whose z span at most `leaves` leaves; each run is its
// first index, and the end closes the list.
std::vector<std::size_t> columnRuns(const std::vector<openvdb::Coord>& origins, int leaves);

// Makes `within` (LeafDistances::within) a leaf's value mask.
template <class Leaf>
void setValueMaskWords(Leaf& leaf, const std::uint64_t* within) {
    for (openvdb::Index w = 0; w < Leaf::SIZE / 64; ++w) leaf.getValueMask().template getWord<std::uint64_t>(w) = within[w];
}

// make(origin, distances, within) for every leaf with a voxel within
// `reach` of the mask, in parallel (within: the voxels within reach as the
// leaf's value-mask words); the leaves it returns (a std::unique_ptr to one
// of tree's leaves, or null) are then added to `tree`.
template <class Tree, class Make>
void addLeavesNear(Tree& tree, const openvdb::MaskTree& mask, int reach, const Make& make) {
    using Leaf = typename Tree::LeafNodeType;
    const std::vector<openvdb::Coord> origins = leafOriginsNear(mask, reach);
    const std::vector<std::size_t> runs = columnRuns(origins, LeafDistances::columnLeaves(reach));
    std::vector<std::unique_ptr<Leaf>> leaves(origins.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs.size() - 1, 4), [&](const tbb::blocked_range<std::size_t>& r) {
        LeafDistances distances(reach);
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
            const std::size_t first = runs[c], last = runs[c + 1] - 1;
            const openvdb::Coord& base = origins[first];
            distances.column(mask, base, (origins[last].z() - base.z()) / 8 + 1);
            for (std::size_t i = first; i <= last; ++i) {
                const int s = (origins[i].z() - base.z()) / 8;
                if (const std::uint8_t* d = distances.leaf(s)) leaves[i] = make(origins[i], d, distances.within(s));
            }
        }
    });
    for (auto& leaf : leaves)
        if (leaf) tree.addLeaf(leaf.release());
}

}  // namespace weft
