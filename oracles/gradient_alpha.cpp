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

class GradientTest {
public:
    GradientTest(const OracleContext& ctx, const OpacityTable& alpha)
        : alpha_(alpha), acc_(ctx.volume.grid->getConstAccessor()), threshold2_(ctx.epsilon * ctx.epsilon) {}
    // c: one of the volume's voxels.
    bool isFeature(const openvdb::Coord& c) {
        double g2 = 0;
        for (int axis = 0; axis < 3; ++axis) {
            openvdb::Coord lo = c, hi = c;
            --lo[axis], ++hi[axis];
            const double g = 0.5 * (alpha_(acc_.getValue(hi)) - alpha_(acc_.getValue(lo)));
            g2 += g * g;
        }
        return g2 > threshold2_;
    }

private:
    const OpacityTable& alpha_;
    openvdb::FloatGrid::ConstAccessor acc_;
    double threshold2_;
};

// The feature voxels, moved by `shift`.
openvdb::MaskGrid::Ptr gradientFeatures(const OracleContext& ctx, const openvdb::Coord& shift) {
    openvdb::MaskGrid::Ptr mask = activeAndFaceNeighbours(*ctx.volume.grid, shift);  // where a gradient can be
    const auto alpha = std::make_unique<OpacityTable>(ctx);
    openvdb::tree::LeafManager<openvdb::MaskTree> leaves(mask->tree());
    leaves.foreach([&](openvdb::MaskTree::LeafNodeType& leaf, std::size_t) {
        GradientTest test(ctx, *alpha);
        for (auto it = leaf.beginValueOn(); it; ++it)
            if (!test.isFeature(it.getCoord() - shift)) leaf.setValueOff(it.pos());
    });
    openvdb::tools::pruneInactive(mask->tree());
    return mask;
}

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
