#pragma once
// What a camera ray sees at its first surface: the surface's own emission
// (from its front) plus direct light from the scene's lights and emitters,
// with shadow rays against the meshes (core/lighting/direct_light.hpp), on
// the Lambert + glossy BRDF the mesh techniques share. Used by the volume
// techniques that end camera rays at surfaces (volume.raymarch, volume.preint,
// volume.adaptive3d).
#include <limits>
#include <string>

#include "core/lighting/brdf.hpp"
#include "core/lighting/direct_light.hpp"
#include "core/base/error.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/sampling/pixel_sampler.hpp"
#include "core/scene/scene.hpp"
#include "core/volume/volume.hpp"

namespace weft {

// Surfaces are lit by point, directional and emissive lights only.
inline void requireSurfaceLights(const Scene& scene, const std::string& technique) {
    if (scene.meshes.empty()) return;
    for (const Light& l : scene.lights)
        if (l.type == LightType::Environment)
            throw Error(technique + " lights surfaces with point, directional and emissive lights only; the scene has an environment light");
}

// The first surface along a camera ray (invalid when none).
inline SurfaceHit firstSurface(const MeshAccel& accel, const Ray& ray) {
    return accel.intersect(toVec3f(ray.origin), toVec3f(ray.dir), 0.0f, std::numeric_limits<float>::infinity());
}

// Outgoing radiance towards the camera at `hit`; sampler dimensions from 2.
inline Vec3f shadeSurface(const Scene& scene, const MeshAccel& accel, const Ray& ray, const SurfaceHit& hit,
                          const PixelSampler& sampler, float eps, std::int64_t& shadowRays) {
    const Vec3f d = toVec3f(ray.dir);
    const Vec3f p = toVec3f(ray.origin) + d * hit.t, wo = -d.unitSafe();
    const Material& mat = scene.materials[accel.material(hit.geom, hit.prim)];
    const bool front = hit.normal.dot(wo) > 0;
    const Vec3f n = front ? hit.normal : -hit.normal;
    Vec3f L = front && mat.emissive() ? mat.emission : Vec3f(0, 0, 0);
    return L + directLight(scene, accel, p, n, wo, Brdf::of(mat), sampler, 2, eps, shadowRays);
}

// Index-space distance from the eye to `hit` on a camera ray, in voxels of
// `vol` (infinity: no hit): where a slice renderer's ray ends.
inline double surfaceIndexDistance(const Volume& vol, const Ray& ray, const SurfaceHit& hit) {
    if (!hit.valid()) return std::numeric_limits<double>::infinity();
    const auto& xf = vol.grid->transform();
    return double(hit.t) * (xf.worldToIndex(ray.origin + ray.dir) - xf.worldToIndex(ray.origin)).length();
}

struct SurfaceCounts {
    std::int64_t surface = 0, shadow = 0;
};

// Shades `hit` and composites it behind the volume already in px
// (premultiplied RGBA): colour = volume + (1 - alpha) x surface, alpha 1.
// An opaque surface of radiance L behind what px (premultiplied RGBA) holds.
inline void compositeBehind(float* px, const Vec3f& L) {
    const float T = 1.0f - px[3];
    px[0] += T * L.x(), px[1] += T * L.y(), px[2] += T * L.z(), px[3] = 1.0f;
}

inline void compositeSurfaceBehind(const Scene& scene, const MeshAccel& accel, const Ray& ray, const SurfaceHit& hit,
                                   const PixelSampler& sampler, float eps, float* px, SurfaceCounts& counts) {
    ++counts.surface;
    compositeBehind(px, shadeSurface(scene, accel, ray, hit, sampler, eps, counts.shadow));
}

}  // namespace weft
