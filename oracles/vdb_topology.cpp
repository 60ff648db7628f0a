// vdb_topology: empty space from the VDB tree. A leaf brick (with its
// one-voxel apron) or active tile whose value range the transfer function
// maps to zero extinction throughout is empty; every other brick is a
// feature, and the distance grows with the distance to it. The field is
// coarse (whole bricks) but cheap: one pass over the tree.
#include "oracles/feature_distance.hpp"

namespace weft {

namespace {

openvdb::MaskGrid::Ptr occupiedBricks(const OracleContext& ctx) {
    const std::vector<BrickRange> bricks = brickRanges(*ctx.volume.grid);
    std::vector<bool> occupied(bricks.size());
    for (std::size_t i = 0; i < bricks.size(); ++i)
        occupied[i] = ctx.volume.tf.extinctionBounds(bricks[i].min, bricks[i].max)[1] > 0;
    return maskOfBricks(bricks, occupied, ctx.volume.grid->transform(), oracleShift(ctx.volume));
}

const OracleRegistrar registrar{{
    "vdb_topology",
    "empty space from the VDB tree: bricks the transfer function maps to zero extinction",
    [](const OracleContext& ctx) { return distanceToFeatures(*occupiedBricks(ctx), ctx, oracleShift(ctx.volume)); },
}};

}  // namespace

}  // namespace weft
