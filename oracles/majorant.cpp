// majorant: per-brick value ranges bound how much the opacity can change
// inside a brick, in the spirit of Open VKL's interval iterators. A brick
// (8^3 leaf with a one-voxel apron, or an active tile) is a feature when its
// slice opacities over the brick's value range differ by more than epsilon
// (a bound on the change anywhere inside); smooth bricks, empty or not, are skipped
// through. Coarser than gradient_alpha, but costs one pass over the tree.
#include <cmath>

#include "oracles/feature_distance.hpp"

namespace weft {

namespace {

openvdb::MaskGrid::Ptr varyingBricks(const OracleContext& ctx) {
    const std::vector<BrickRange> bricks = brickRanges(*ctx.volume.grid);
    std::vector<bool> varying(bricks.size());
    for (std::size_t i = 0; i < bricks.size(); ++i) {
        const auto ext = ctx.volume.tf.extinctionBounds(bricks[i].min, bricks[i].max);
        const double alphaChange = std::expm1(-ext[0] * ctx.sliceSpacing) - std::expm1(-ext[1] * ctx.sliceSpacing);
        varying[i] = alphaChange > ctx.epsilon;
    }
    return maskOfBricks(bricks, varying, ctx.volume.grid->transform(), oracleShift(ctx.volume));
}

const OracleRegistrar registrar{{
    "majorant",
    "per-brick value-range bound on opacity change (smooth bricks are skipped, empty or not)",
    [](const OracleContext& ctx) { return distanceToFeatures(*varyingBricks(ctx), ctx, oracleShift(ctx.volume)); },
}};

}  // namespace

}  // namespace weft
