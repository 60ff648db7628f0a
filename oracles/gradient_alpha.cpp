// gradient_alpha: the paper's ad-hoc oracle (Kraus et al. 2007, Section 4):
// the distance to the nearest voxel whose opacity-gradient magnitude exceeds
// epsilon. Opacity is that of one slice-spacing segment through the transfer
// function, so the oracle is built once per volume, transfer function and
// spacing. Gradients are central differences over voxels next to any active
// voxel (the background beyond counts, so edges of the data are features).
#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>

#include <array>
#include <cmath>
#include <memory>

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

}  // namespace

openvdb::MaskGrid::Ptr gradientFeatures(const OracleContext& ctx, const openvdb::Coord& shift) {
    openvdb::MaskGrid::Ptr mask = activeAndFaceNeighbours(*ctx.volume.grid, shift);  // where a gradient can be
    const auto alpha = std::make_unique<OpacityTable>(ctx);
    const double threshold2 = ctx.epsilon * ctx.epsilon;
    openvdb::tree::LeafManager<openvdb::MaskTree> leaves(mask->tree());
    leaves.foreach([&](openvdb::MaskTree::LeafNodeType& leaf, std::size_t) {
        BlockOpacity block(ctx.volume.grid->tree(), *alpha);
        block.load(leaf.origin() - shift);  // shift is a whole number of leaves
        for (auto it = leaf.beginValueOn(); it; ++it) {
            const openvdb::Index n = it.pos();
            if (!(block.gradient2(int(n >> 6), int((n >> 3) & 7), int(n & 7)) > threshold2)) leaf.setValueOff(n);
        }
    });
    openvdb::tools::pruneInactive(mask->tree());
    return mask;
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
