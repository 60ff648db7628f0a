#pragma once
// Next-event estimation on a surface: light arriving at p (normal n,
// towards wo) straight from the scene's lights, times the BRDF. One sample
// of the emissive triangles (sampler dimensions dim..dim+2) and every point
// and directional light exactly; each shadow ray is counted. Shared by
// mesh.pathtrace and lighting.adaptive_indirect, so both see the same light.
// `media` (the deferred techniques' volumes) attenuates each shadow ray.
#include <cmath>
#include <cstdint>

#include "core/lighting/brdf.hpp"
#include "core/lighting/delta_lights.hpp"
#include "core/lighting/emitters.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/sampling/pixel_sampler.hpp"
#include "core/scene/scene.hpp"

namespace weft {

class SegmentAttenuation;  // core/lighting/volume_attenuation.hpp, which defines this:
// light x the transmittance from origin along dir for distance.
Vec3f attenuated(SegmentAttenuation& media, const Vec3f& light, const Vec3f& origin, const Vec3f& dir, float distance);

inline Vec3f directLight(const Scene& scene, const MeshAccel& accel, const Vec3f& p, const Vec3f& n, const Vec3f& wo,
                         const Brdf& brdf, const PixelSampler& sampler, std::uint32_t dim, float eps,
                         std::int64_t& shadowRays, SegmentAttenuation* media = nullptr) {
    Vec3f sum(0, 0, 0);
    const Vec3f origin = p + n * eps;
    const Emitters& emitters = scene.emitters();
    if (!emitters.empty()) {
        const EmitterSample e = emitters.sample(sampler.get(dim), sampler.get(dim + 1), sampler.get(dim + 2));
        const EmitterView v = viewFrom(e, origin);
        const Vec3f& to = v.wi;
        const float d = v.distance, d2 = v.distance2, cosX = n.dot(to), cosL = v.cosLight;
        if (cosX > 0 && cosL > 0 && d > 2 * eps) {
            ++shadowRays;
            if (!accel.occluded(origin, to, 0.0f, d * (1.0f - 1e-4f))) {
                const Vec3f light = brdf.eval(wo, to, n) * e.radiance * (cosX * cosL / (d2 * e.pdfArea));
                sum += media ? attenuated(*media, light, origin, to, d) : light;
            }
        }
    }
    for (const Light& light : scene.lights) {
        const DeltaIllumination li = illuminate(light, origin);
        const float cosX = n.dot(li.wi);
        if (cosX <= 0) continue;
        ++shadowRays;
        if (!accel.occluded(origin, li.wi, 0.0f, li.distance * (1.0f - 1e-4f))) {
            const Vec3f light = brdf.eval(wo, li.wi, n) * li.irradiance * cosX;
            sum += media ? attenuated(*media, light, origin, li.wi, li.distance) : light;
        }
    }
    return sum;
}

}  // namespace weft
