#pragma once
// Next-event estimation through participating media: light arriving at a
// point on a surface or inside a medium, from one sample of the emissive
// triangles and every point and directional light, each through a shadow
// ray that surfaces block and volumes attenuate (delta or ratio tracking).
// The caller's `response(wi)` is what the point does with light from wi:
// BRDF x cosine on a surface, the phase function in a medium (zero: no
// shadow ray is traced).
#include <cmath>
#include <cstdint>

#include "core/lighting/delta_lights.hpp"
#include "core/lighting/emitters.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/scene/scene.hpp"
#include "core/volume/media/medium.hpp"

namespace weft {

enum class ShadowTracking { Delta, Ratio };

// Shadow rays of one thread: the mesh test first (cheap, and an occluder
// makes the volumes irrelevant), then the volumes between.
class ShadowRays {
public:
    ShadowRays(const MeshAccel& accel, const Medium& medium, ShadowTracking tracking)
        : accel_(accel), ray_(medium), tracking_(tracking) {}

    Vec3d transmittance(const Vec3f& origin, const Vec3f& dir, float distance, Rng& rng) {
        ++traced;
        if (accel_.occluded(origin, dir, 0.0f, distance * (1.0f - 1e-4f))) return Vec3d(0.0);
        ray_.reset(toVec3d(origin), toVec3d(dir), double(distance));
        if (ray_.empty()) return Vec3d(1.0);
        return tracking_ == ShadowTracking::Ratio ? ratioTrackingTransmittance(ray_, rng, collisions)
                                                  : deltaTrackingTransmittance(ray_, rng, collisions);
    }
    std::int64_t lookups() const { return ray_.lookups; }
    // The shutter time of the shadow rays that follow (moving volumes).
    void setTime(double frames) { ray_.setTime(frames); }

    std::int64_t traced = 0, collisions = 0;

private:
    const MeshAccel& accel_;
    MediumRay ray_;
    ShadowTracking tracking_;
};

// u0..u2 pick the emitter point.
// emitters: the scene's (empty for a scene without meshes, which has none).
template <class Response>
Vec3f directLightThroughMedia(const Scene& scene, const Emitters& emitters, const Vec3f& origin, const Response& response,
                              float u0, float u1, float u2, float eps, ShadowRays& shadow, Rng& rng) {
    Vec3f sum(0, 0, 0);
    if (!emitters.empty()) {
        const EmitterSample e = emitters.sample(u0, u1, u2);
        const EmitterView v = viewFrom(e, origin);
        const Vec3f& to = v.wi;
        const float d = v.distance, d2 = v.distance2, cosL = v.cosLight;
        const Vec3f f = cosL > 0 && d > 2 * eps ? response(to) : Vec3f(0, 0, 0);
        if (f != Vec3f(0, 0, 0))
            sum += f * e.radiance * toVec3f(shadow.transmittance(origin, to, d, rng)) * (cosL / (d2 * e.pdfArea));
    }
    for (const Light& light : scene.lights) {
        const DeltaIllumination li = illuminate(light, origin);
        const Vec3f f = response(li.wi);
        if (f == Vec3f(0, 0, 0)) continue;
        sum += f * li.irradiance * toVec3f(shadow.transmittance(origin, li.wi, li.distance, rng));
    }
    return sum;
}

}  // namespace weft
