#pragma once
// Incident indirect illumination at a G-buffer texel, one Monte Carlo sample
// at a time: a cosine-distributed direction from the texel, then a path
// with mesh.pathtrace's conventions (next-event estimation at every vertex:
// one emitter point chosen by power plus every point/directional light;
// Lambert + Phong BRDF sampling; Russian roulette from `rrDepth` vertices;
// emission is never counted at a bounce, since next-event estimation at the
// texel already holds the direct light). The estimate is the irradiance
// E = integral of L_indirect cos over the hemisphere (pi L for a cosine
// sample); a diffuse surface reflects kd / pi * E of it. With `media`
// (the scene's volumes, one SegmentAttenuation per thread) every path
// segment and shadow ray is attenuated by its transmittance.
#include <cstdint>

#include "core/lighting/volume_attenuation.hpp"
#include "core/screen/gbuffer.hpp"
#include "core/sampling/pixel_sampler.hpp"

namespace weft {

struct PathRayCounts {
    std::int64_t bounce = 0, shadow = 0;
};

class IndirectEstimator {
public:
    // bounces: 1 = light reflected once on the way (the direct light seen at
    // the first bounce), 2 = twice, ...
    IndirectEstimator(const Scene& scene, int bounces, int rrDepth);

    Vec3f irradiance(const GTexel& texel, const PixelSampler& sampler, PathRayCounts& counts,
                     SegmentAttenuation* media = nullptr) const;
    // Direct light reflected towards wo at texel (kd and ks applied), with
    // dimensions dim..dim+2 of the sampler; point lights exact.
    Vec3f direct(const Vec3f& p, const Vec3f& n, const Vec3f& wo, std::uint32_t material, const PixelSampler& sampler,
                 std::uint32_t dim, PathRayCounts& counts, SegmentAttenuation* media = nullptr) const;

private:
    const Scene& scene_;
    int bounces_, rrDepth_;
    float eps_;
};

}  // namespace weft
