#include "core/lighting/emitters.hpp"

#include <algorithm>
#include <cmath>

namespace weft {

Emitters::Emitters(const std::vector<TriangleMesh>& meshes, const std::vector<Material>& materials) {
    for (const TriangleMesh& m : meshes)
        for (std::size_t t = 0; t < m.triangleCount(); ++t) {
            const Material& mat = materials[m.material[t]];
            if (!mat.emissive()) continue;
            Tri tri{m.positions[m.indices[3 * t]], m.positions[m.indices[3 * t + 1]], m.positions[m.indices[3 * t + 2]], {}, mat.emission, 0};
            const Vec3f cross = (tri.b - tri.a).cross(tri.c - tri.a);
            tri.area = 0.5f * cross.length();
            if (!(tri.area > 0)) continue;  // degenerate: emits nothing
            tri.normal = cross / (2.0f * tri.area);
            triangles_.push_back(tri);
        }
    double running = 0;
    for (const Tri& t : triangles_) {
        running += double(t.area) * std::max(1e-6f, luminance(t.radiance));
        cdf_.push_back(float(running));
        power_ += t.radiance * float(M_PI * t.area);
    }
    totalWeight_ = float(running);
    for (float& c : cdf_) c /= totalWeight_;
    if (!cdf_.empty()) cdf_.back() = 1.0f;
}

EmitterSample Emitters::sample(float u, float v, float w) const {
    const std::size_t i = std::min<std::size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin(), triangles_.size() - 1);
    const Tri& t = triangles_[i];
    // Square-root warp: uniform by area on the triangle.
    const float su = std::sqrt(v);
    const float b0 = 1 - su, b1 = w * su;
    EmitterSample s;
    s.position = t.a * b0 + t.b * b1 + t.c * (1 - b0 - b1);
    s.normal = t.normal;
    s.radiance = t.radiance;
    const float pick = (cdf_[i] - (i ? cdf_[i - 1] : 0.0f));
    s.pdfArea = pick / t.area;
    return s;
}

}  // namespace weft
