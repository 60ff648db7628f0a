#pragma once
// Deterministic transmittance along a MediumRay, for the deferred lighting
// techniques: their images must be free of estimator noise (a shadow ray
// per VPL and texel cannot afford many tracking samples) and the same at
// any thread count. The optical depth is integrated by the midpoint rule in
// steps of at most `stepVoxels` voxel lengths (along the ray, of the finest
// volume it crosses) over the stretches where the per-brick majorant is
// non-zero; empty bricks are skipped whole, and a stretch of constant
// density integrates exactly. Past an optical depth of kOpaqueDepth in
// every channel the ray counts as opaque (0).
#include <cstdint>

#include "core/volume/media/medium.hpp"

namespace weft {

constexpr double kOpaqueDepth = 40.0;  // exp(-40) ~ 4e-18

// exp(-optical depth) per channel over [0, ray.end()); adds the midpoint
// samples taken to `steps`.
Vec3d marchedTransmittance(MediumRay& ray, double stepVoxels, std::int64_t& steps);

}  // namespace weft
