// gradient_alpha: the paper's ad-hoc oracle (Kraus et al. 2007, Section 4):
// the distance to the nearest voxel whose opacity-gradient magnitude exceeds
// epsilon. Opacity is that of one slice-spacing segment through the transfer
// function, so the oracle is built once per volume, transfer function and
// spacing. Gradients are central differences over voxels next to any active
// voxel (the background beyond counts, so edges of the data are features).
#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/volume/octant_shift.hpp"
#include "oracles/feature_distance.hpp"

namespace weft {

namespace {

// Slice opacity of a data value through a table over the transfer
// function's range (one exp per entry instead of six per voxel).
class OpacityTable {
public:
    OpacityTable(const OracleContext& ctx) : lo_(ctx.volume.tf.rangeMin()) {
        const double hi = ctx.volume.tf.rangeMax();
        scale_ = kEntries / (hi - lo_);
        for (int i = 0; i <= kEntries; ++i)
            alpha_[i] = sliceOpacity(ctx.volume, ctx.sliceSpacing, float(lo_ + i / scale_));
    }
    double operator()(float value) const {
        double x = (double(value) - lo_) * scale_;
        if (!(x > 0)) return alpha_[0];  // also NaN
        if (x >= kEntries) return alpha_[kEntries];
        const int i = int(x);
        return alpha_[i] + (x - i) * (alpha_[i + 1] - alpha_[i]);
    }

private:
    static constexpr int kEntries = 4096;
    double lo_, scale_;
    std::array<double, kEntries + 1> alpha_;
};

// The slice opacity of one 8^3 block of the volume and of its six face
// neighbours' layers next to it: every value a central difference inside
// the block reads, each looked up and put through the table once (one
// voxel's gradient reads six of them), and read from the leaves' buffers
// rather than through an accessor's tree walk per value.
class BlockOpacity {
public:
    BlockOpacity(const openvdb::FloatTree& tree, const OpacityTable& alpha) : tree_(tree), alpha_(alpha) {}

    // Loads the block whose lowest voxel is `origin` (a multiple of 8).
    void load(const openvdb::Coord& origin) {
        fill(origin, 1, 1, 1, 8, 8, 8);
        for (int axis = 0; axis < 3; ++axis)
            for (int side : {0, 9}) {
                int at[3] = {1, 1, 1}, size[3] = {8, 8, 8};
                at[axis] = side, size[axis] = 1;
                fill(origin, at[0], at[1], at[2], size[0], size[1], size[2]);
            }
    }
    // Squared central-difference gradient of opacity at block voxel (x, y, z), each in [0, 8).
    double gradient2(int x, int y, int z) const {
        const int i = index(x + 1, y + 1, z + 1);
        double g2 = 0;
        for (const int step : {kSide * kSide, kSide, 1}) {
            const double g = 0.5 * (cells_[i + step] - cells_[i - step]);
            g2 += g * g;
        }
        return g2;
    }

private:
    static constexpr int kSide = 10;
    static int index(int x, int y, int z) { return (x * kSide + y) * kSide + z; }

    // The opacities of block cells [at, at + size) (the block's voxel
    // (0, 0, 0) is cell (1, 1, 1)), all inside one leaf of the tree.
    void fill(const openvdb::Coord& origin, int ax, int ay, int az, int sx, int sy, int sz) {
        const openvdb::Coord first = origin + openvdb::Coord(ax - 1, ay - 1, az - 1);
        const auto* leaf = tree_.probeConstLeaf(first);
        const float* values = leaf ? leaf->buffer().data() : nullptr;  // loads a delay-loaded leaf once
        const double tile = values ? 0.0 : alpha_(tree_.getValue(first));
        for (int x = ax; x < ax + sx; ++x)
            for (int y = ay; y < ay + sy; ++y)
                for (int z = az; z < az + sz; ++z)
                    cells_[index(x, y, z)] = values ? alpha_(values[leafOffset(x - 1, y - 1, z - 1)]) : tile;
    }
    // Voxel (x, y, z) of the block's leaf, each wrapped into [0, 8) (an apron cell lies in the neighbouring leaf).
    static openvdb::Index leafOffset(int x, int y, int z) { return openvdb::Index(((x & 7) << 6) | ((y & 7) << 3) | (z & 7)); }

    const openvdb::FloatTree& tree_;
    const OpacityTable& alpha_;
    std::array<double, kSide * kSide * kSide> cells_;
};

// A leaf's 512 voxel bits as OpenVDB lays them out: word x holds the
// slab of voxels (x, y, z) at bit 8 y + z.
using LeafBits = std::array<std::uint64_t, 8>;
constexpr std::uint64_t kZLow = 0x0101010101010101ull;   // z = 0 of every row
constexpr std::uint64_t kZHigh = 0x8080808080808080ull;  // z = 7
constexpr std::uint64_t kYLow = 0xffull;                  // y = 0
constexpr int kYHighShift = 56;                           // y = 7 starts here

LeafBits bitsOf(const openvdb::util::NodeMask<3>& mask) {
    LeafBits b;
    for (int x = 0; x < 8; ++x) b[x] = mask.getWord<std::uint64_t>(x);
    return b;
}

// The face neighbours of `active` inside its own block (the voxels themselves included).
LeafBits dilatedInside(const LeafBits& active) {
    LeafBits out;
    for (int x = 0; x < 8; ++x) {
        const std::uint64_t w = active[x];
        out[x] = w | (w << 8) | (w >> 8) | ((w << 1) & ~kZLow) | ((w >> 1) & ~kZHigh);
        if (x > 0) out[x] |= active[x - 1];
        if (x < 7) out[x] |= active[x + 1];
    }
    return out;
}

// The voxels of a block whose face neighbours across its face (axis, side:
// -1 the low face, +1 the high) are active in the block `beyond` there: the
// layer of this block next to that face.
LeafBits acrossFace(const LeafBits& beyond, int axis, int side) {
    LeafBits out{};
    if (axis == 0) {
        if (side < 0) out[0] = beyond[7];
        else out[7] = beyond[0];
        return out;
    }
    for (int x = 0; x < 8; ++x) {
        const std::uint64_t w = beyond[x];
        if (axis == 1) out[x] = side < 0 ? (w >> kYHighShift) : (w & kYLow) << kYHighShift;
        else out[x] = side < 0 ? (w & kZHigh) >> 7 : (w & kZLow) << 7;
    }
    return out;
}

bool anyBit(const LeafBits& b) {
    std::uint64_t any = 0;
    for (std::uint64_t w : b) any |= w;
    return any != 0;
}

// Of the candidate voxels of the block at `origin` (volume voxels), those
// whose gradient exceeds the threshold: a mask leaf at origin + shift, or
// null when there are none.
std::unique_ptr<openvdb::MaskTree::LeafNodeType> testBlock(BlockOpacity& block, const openvdb::Coord& origin, const LeafBits& candidates,
                                                           double threshold2, const openvdb::Coord& shift) {
    block.load(origin);
    LeafBits marked{};
    for (int x = 0; x < 8; ++x)
        for (std::uint64_t w = candidates[x]; w; w &= w - 1) {
            const int bit = std::countr_zero(w);
            if (block.gradient2(x, bit >> 3, bit & 7) > threshold2) marked[x] |= std::uint64_t(1) << bit;
        }
    if (!anyBit(marked)) return nullptr;
    auto leaf = std::make_unique<openvdb::MaskTree::LeafNodeType>(origin + shift, false);
    for (int x = 0; x < 8; ++x) leaf->getValueMask().getWord<std::uint64_t>(x) = marked[x];
    return leaf;
}

// The features found from one data leaf: in its own block, and in the
// neighbouring blocks that hold no data leaf (the layer next to the leaf).
struct LeafFeatures {
    std::vector<std::unique_ptr<openvdb::MaskTree::LeafNodeType>> own, beside;
};

// gradientFeatures for a tree of leaves only: the candidates (active voxels
// and their face neighbours) come a leaf at a time from the value masks
// with bit shifts, and are tested in the same pass, so no candidate tree is
// built or dilated; the features are the same voxels.
openvdb::MaskGrid::Ptr featuresOfLeaves(const OracleContext& ctx, const openvdb::Coord& shift, const OpacityTable& alpha) {
    using Leaf = openvdb::FloatTree::LeafNodeType;
    const openvdb::FloatTree& tree = ctx.volume.grid->tree();
    std::vector<const Leaf*> leaves;
    tree.getNodes(leaves);
    const double threshold2 = ctx.epsilon * ctx.epsilon;
    tbb::enumerable_thread_specific<LeafFeatures> found;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        LeafFeatures& out = found.local();
        BlockOpacity block(tree, alpha);
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const openvdb::Coord origin = leaves[i]->origin();
            const LeafBits active = bitsOf(leaves[i]->getValueMask());
            LeafBits candidates = dilatedInside(active);
            for (int axis = 0; axis < 3; ++axis)
                for (int side : {-1, 1}) {
                    openvdb::Coord next = origin;
                    next[axis] += 8 * side;
                    if (const Leaf* beyond = tree.probeConstLeaf(next)) {
                        const LeafBits in = acrossFace(bitsOf(beyond->getValueMask()), axis, side);
                        for (int x = 0; x < 8; ++x) candidates[x] |= in[x];
                    } else if (anyBit(active)) {  // no leaf there: its layer next to this leaf is tested from here
                        if (auto leaf = testBlock(block, next, acrossFace(active, axis, -side), threshold2, shift)) out.beside.push_back(std::move(leaf));
                    }
                }
            if (auto leaf = testBlock(block, origin, candidates, threshold2, shift)) out.own.push_back(std::move(leaf));
        }
    });
    openvdb::MaskGrid::Ptr mask = shiftedMask(ctx.volume.grid->transform(), shift);
    openvdb::MaskTree& features = mask->tree();
    for (LeafFeatures& f : found)
        for (auto& leaf : f.own) features.addLeaf(leaf.release());  // one per data leaf: no two alike
    for (LeafFeatures& f : found)
        for (auto& leaf : f.beside) {
            // Blocks beside several data leaves get a layer from each.
            if (auto* held = features.probeLeaf(leaf->origin())) held->getValueMask() |= leaf->getValueMask();
            else features.addLeaf(leaf.release());
        }
    return mask;
}

// gradientFeatures through a candidate tree: OpenVDB's dilation of the
// active topology, active tiles included.
openvdb::MaskGrid::Ptr featuresOfCandidates(const OracleContext& ctx, const openvdb::Coord& shift, const OpacityTable& alpha) {
    openvdb::MaskGrid::Ptr mask = activeAndFaceNeighbours(*ctx.volume.grid, shift);  // where a gradient can be
    const double threshold2 = ctx.epsilon * ctx.epsilon;
    openvdb::tree::LeafManager<openvdb::MaskTree> leaves(mask->tree());
    leaves.foreach([&](openvdb::MaskTree::LeafNodeType& leaf, std::size_t) {
        BlockOpacity block(ctx.volume.grid->tree(), alpha);
        block.load(leaf.origin() - shift);  // shift is a whole number of leaves
        for (auto it = leaf.beginValueOn(); it; ++it) {
            const openvdb::Index n = it.pos();
            if (!(block.gradient2(int(n >> 6), int((n >> 3) & 7), int(n & 7)) > threshold2)) leaf.setValueOff(n);
        }
    });
    openvdb::tools::pruneInactive(mask->tree());
    return mask;
}

}  // namespace

openvdb::MaskGrid::Ptr gradientFeatures(const OracleContext& ctx, const openvdb::Coord& shift) {
    const auto alpha = std::make_unique<OpacityTable>(ctx);
    if (ctx.volume.grid->tree().activeTileCount() == 0) return featuresOfLeaves(ctx, shift, *alpha);
    return featuresOfCandidates(ctx, shift, *alpha);
}

namespace {

const OracleRegistrar registrar{{
    "gradient_alpha",
    "distance to the nearest voxel with |grad opacity| > epsilon (the paper's oracle)",
    [](const OracleContext& ctx) {
        const openvdb::Coord shift = oracleShift(ctx.volume);
        return distanceToFeatures(*gradientFeatures(ctx, shift), ctx, shift);
    },
}};

}  // namespace

}  // namespace weft
