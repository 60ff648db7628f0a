#pragma once
// What the precomputed oracles share. Each marks "feature" voxels where
// samples must stay dense; distanceToFeatures() turns that mask into a
// sampling-distance field. Skipping from a point is safe while the segment
// stays clear of every feature, so the distance is the Chebyshev distance to
// the nearest feature voxel, which never exceeds the Euclidean one.
#include <openvdb/openvdb.h>

#include <vector>

#include "core/volume/grid/leaf_reach.hpp"
#include "oracles/oracle.hpp"

namespace weft {

// Opacity of one slice-spacing segment at a raw data value.
double sliceOpacity(const Volume& volume, double spacing, float value);

// Where the oracles' trees put the volume's voxel v: at v + oracleShift, a
// whole number of leaves that moves every voxel the field can hold (the
// active box, grown by the rings around features) above the index origin.
// A tree over a volume around the origin then keeps one top node instead of
// eight (core/volume/grid/octant_shift.hpp). Zero for an empty volume.
openvdb::Coord oracleShift(const Volume& volume);

// The active voxels of a grid and their face neighbours, moved by `shift`:
// every voxel where a central difference over the grid can be non-zero
// (the background beyond the data counts, so its edges are included).
openvdb::MaskGrid::Ptr activeAndFaceNeighbours(const openvdb::FloatGrid& grid, const openvdb::Coord& shift);
openvdb::MaskGrid::Ptr activeAndFaceNeighbours(const openvdb::Vec3SGrid& grid, const openvdb::Coord& shift);

// The sampling-distance field of a feature mask, in voxels: ctx.sliceSpacing
// on and next to features, growing by one voxel per voxel of Chebyshev
// distance, capped (and constant outside the stored band) at
// 2^lmax * sliceSpacing. An emitting volume's emission features
// (emissionFeatures) join the mask: every precomputed oracle keeps samples
// dense where the glow changes, whatever it reads from the density.
// `features` holds the volume's voxels moved by `shift` (oracleShift), and
// so does the field.
OracleField distanceToFeatures(const openvdb::MaskGrid& features, const OracleContext& ctx,
                               const openvdb::Coord& shift = openvdb::Coord(0));

// The two ways distanceToFeatures builds the field of a mask; the values
// are the same. By rings: OpenVDB's dilation one ring at a time, any cap.
// By blocks: each leaf within reach of a feature on its own, in parallel
// (core/volume/grid/leaf_reach.hpp); for at most kMaxLeafReach rings.
OracleField distanceFieldByRings(const openvdb::MaskGrid& features, const OracleContext& ctx);
OracleField distanceFieldByBlocks(const openvdb::MaskGrid& features, const OracleContext& ctx);

// gradient_alpha's features: the voxels (active ones and their face
// neighbours) where the central-difference gradient of one slice's opacity
// exceeds ctx.epsilon per voxel, moved by `shift` (a multiple of 8).
openvdb::MaskGrid::Ptr gradientFeatures(const OracleContext& ctx, const openvdb::Coord& shift = openvdb::Coord(0));

// Voxels where one slice's emitted radiance (the largest channel of the
// emission grid x the slice spacing) has a gradient above ctx.epsilon per
// voxel, the emission's counterpart of gradient_alpha's opacity gradient.
// Linear interpolation between distant samples is exact where emission is
// constant, so only its changes are features. Needs ctx.volume.emission.
// The mask holds them moved by `shift`.
openvdb::MaskGrid::Ptr emissionFeatures(const OracleContext& ctx, const openvdb::Coord& shift = openvdb::Coord(0));

// The value range of one region of the grid: an 8^3 leaf brick with a
// one-voxel apron (so a step between neighbouring bricks shows in both), or
// an active tile (constant).
struct BrickRange {
    openvdb::CoordBBox box;
    float min, max;
};
std::vector<BrickRange> brickRanges(const openvdb::FloatGrid& grid);

// Marks whole bricks as features, moved by `shift`.
openvdb::MaskGrid::Ptr maskOfBricks(const std::vector<BrickRange>& bricks, const std::vector<bool>& isFeature,
                                    const openvdb::math::Transform& transform, const openvdb::Coord& shift);

}  // namespace weft
