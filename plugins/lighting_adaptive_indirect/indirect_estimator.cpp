#include "plugins/lighting_adaptive_indirect/indirect_estimator.hpp"

#include <algorithm>
#include <limits>

#include "core/lighting/brdf.hpp"
#include "core/lighting/delta_lights.hpp"
#include "core/lighting/direct_light.hpp"
#include "core/mesh/mesh_accel.hpp"

namespace weft {

namespace {
constexpr std::uint32_t kDimsPerVertex = 8;  // 3 light, 3 BRDF, 1 roulette, 1 spare
}

IndirectEstimator::IndirectEstimator(const Scene& scene, int bounces, int rrDepth)
    : scene_(scene), bounces_(bounces), rrDepth_(rrDepth), eps_(rayEpsilon(scene)) {
    scene.accel(), scene.emitters();  // built before any parallel use
}

Vec3f IndirectEstimator::direct(const Vec3f& p, const Vec3f& n, const Vec3f& wo, std::uint32_t material,
                                const PixelSampler& sampler, std::uint32_t dim, PathRayCounts& counts,
                                SegmentAttenuation* media) const {
    return directLight(scene_, scene_.accel(), p, n, wo, Brdf::of(scene_.materials[material]), sampler, dim, eps_,
                       counts.shadow, media);
}

Vec3f IndirectEstimator::irradiance(const GTexel& t, const PixelSampler& sampler, PathRayCounts& counts,
                                    SegmentAttenuation* media) const {
    if (t.background()) return Vec3f(0, 0, 0);
    const MeshAccel& accel = scene_.accel();
    Vec3f o = t.position + t.normal * eps_, d = sampleCosine(t.normal, sampler.get(0), sampler.get(1));
    Vec3f L(0, 0, 0), throughput(float(M_PI), float(M_PI), float(M_PI));  // pi: cosine / pdf
    for (int bounce = 1; bounce <= bounces_; ++bounce) {
        ++counts.bounce;
        const SurfaceHit hit = accel.intersect(o, d, 0.0f, std::numeric_limits<float>::infinity());
        if (!hit.valid()) break;
        if (media) throughput *= media->along(o, d, hit.t);
        const Vec3f p = o + d * hit.t, wo = -d;
        const Vec3f n = hit.normal.dot(wo) > 0 ? hit.normal : -hit.normal;
        const std::uint32_t material = accel.material(hit.geom, hit.prim);
        const std::uint32_t dim = 2 + kDimsPerVertex * std::uint32_t(bounce - 1);
        L += throughput * direct(p, n, wo, material, sampler, dim, counts, media);
        if (bounce == bounces_) break;
        if (bounce + 1 >= rrDepth_) {  // the texel is vertex 1, this hit vertex bounce + 1
            const float q = std::min(0.95f, std::max({throughput.x(), throughput.y(), throughput.z()}) / float(M_PI));
            if (sampler.get(dim + 6) >= q) break;
            throughput /= q;
        }
        const Brdf brdf = Brdf::of(scene_.materials[material]);
        const Vec3f wi = brdf.sample(wo, n, sampler.get(dim + 3), sampler.get(dim + 4), sampler.get(dim + 5));
        const float cosI = n.dot(wi), pdf = brdf.pdf(wo, wi, n);
        if (cosI <= 0 || !(pdf > 0)) break;
        throughput *= brdf.eval(wo, wi, n) * (cosI / pdf);
        o = p + n * eps_, d = wi;
    }
    return L;
}

}  // namespace weft
