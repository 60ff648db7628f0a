#pragma once
// Point and directional lights seen from a surface point: the direction to
// the light, how far it is, and the irradiance it brings on a surface facing
// it. Shared by the mesh techniques so they light scenes identically.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/base/error.hpp"
#include "core/scene/scene.hpp"

namespace weft {

struct DeltaIllumination {
    Vec3f wi;        // unit, towards the light
    float distance;  // infinity for directional lights
    Vec3f irradiance;  // on a surface facing the light (before the cosine)
};

inline DeltaIllumination illuminate(const Light& light, const Vec3f& x) {
    const Vec3f color = light.color * float(light.intensity);
    if (light.type == LightType::Directional) {
        const Vec3f d(float(-light.direction.x()), float(-light.direction.y()), float(-light.direction.z()));
        return {d, std::numeric_limits<float>::infinity(), color};
    }
    const Vec3f to = Vec3f(float(light.position.x()), float(light.position.y()), float(light.position.z())) - x;
    const float d2 = std::max(to.lengthSqr(), 1e-12f), d = std::sqrt(d2);
    return {to / d, d, color / d2};
}

// Mesh techniques light with area, point and directional lights only.
inline void requireMeshLights(const Scene& scene, const std::string& technique) {
    if (scene.meshes.empty()) throw Error(technique + " renders meshes; the scene '" + scene.source + "' has none");
    for (const Light& l : scene.lights)
        if (l.type == LightType::Environment) throw Error(technique + " does not support environment lights (use point, directional or emissive materials)");
}

// Distance scale for ray offsets: a small fraction of the scene's size.
inline float rayEpsilon(const Scene& scene) {
    const BBoxd box = scene.worldBox();
    return float(1e-5 * std::max(1e-3, box.extents().length()));
}

}  // namespace weft
