#pragma once
// Area lights: every triangle whose material emits. Points are sampled on
// them in proportion to emitted power (area x luminance of Ke), so bright
// small lights get their share of samples.
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace weft {

struct EmitterSample {
    Vec3f position;
    Vec3f normal;     // the emitting side
    Vec3f radiance;   // Ke
    float pdfArea = 0;  // density per unit area of picking this point
};

// An emitter point seen from `origin`: the unit direction towards it, its
// distance (and square), and the cosine at the emitter (> 0: it faces origin).
struct EmitterView {
    Vec3f wi;
    float distance, distance2, cosLight;
};

inline EmitterView viewFrom(const EmitterSample& e, const Vec3f& origin) {
    Vec3f to = e.position - origin;
    const float d2 = to.lengthSqr(), d = std::sqrt(d2);
    to /= d;
    return {to, d, d2, -e.normal.dot(to)};
}

class Emitters {
public:
    Emitters() = default;
    Emitters(const std::vector<TriangleMesh>& meshes, const std::vector<Material>& materials);

    bool empty() const { return triangles_.empty(); }
    std::size_t triangleCount() const { return triangles_.size(); }
    // u picks the triangle, (v, w) the point on it (uniform by area).
    EmitterSample sample(float u, float v, float w) const;
    // Total emitted power, sum of pi * area * Ke (per channel).
    Vec3f power() const { return power_; }

private:
    struct Tri {
        Vec3f a, b, c, normal, radiance;
        float area;
    };
    std::vector<Tri> triangles_;
    std::vector<float> cdf_;  // normalized, cdf_.back() == 1
    float totalWeight_ = 0;
    Vec3f power_{0, 0, 0};
};

inline float luminance(const Vec3f& c) { return 0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z(); }

}  // namespace weft
