// mesh.pathtrace — unbiased path tracing of meshes, the reference the VPL
// technique is measured against.
//
// Camera paths bounce on Lambertian + Phong surfaces (core/lighting/brdf.hpp). At every
// vertex, next-event estimation samples one point on the emitters (by power)
// and every point/directional light, with a shadow ray each; emission is
// counted only where a camera ray sees an emitter directly, so no light is
// counted twice. Russian roulette ends paths after `rr_depth` vertices with
// a survival chance equal to the throughput's largest component. Samples
// come from a stratified sampler (Latin hypercube over the pixel's spp), a
// pure function of seed, pixel, sample and dimension: images are identical
// for any thread count.
//
// Parameters (see `weft help mesh.pathtrace`):
//   max_depth  surface interactions per path: 1 = direct light only,
//              2 = plus one indirect bounce (the VPL techniques' one bounce)
//   rr_depth   vertices before Russian roulette starts
//   glossy     phong | blinn: the glossy lobe of materials with Ks
//   jitter     sample positions inside the pixel; false shoots every sample
//              through the pixel centre, the way G-buffer techniques see it
//
// Counters: rays.camera, rays.bounce, rays.shadow.
#include <algorithm>
#include <limits>

#include "core/lighting/brdf.hpp"
#include "core/lighting/delta_lights.hpp"
#include "core/lighting/direct_light.hpp"
#include "core/lighting/emitters.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/sampling/pixel_loop.hpp"
#include "core/sampling/pixel_sampler.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

struct PathCounts {
    std::int64_t bounce = 0, shadow = 0;
};

class PathTracer final : public Technique {
public:
    PathTracer(const Scene& scene, const ParamSet& p)
        : maxDepth_(int(p.getInt("max_depth"))), rrDepth_(int(p.getInt("rr_depth"))), jitter_(p.getBool("jitter")),
          model_(Brdf::modelNamed(p.getString("glossy"))) {
        requireMeshLights(scene, "mesh.pathtrace");
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        const MeshAccel& accel = scene.accel();  // built before the pixel loop
        scene.emitters();
        eps_ = rayEpsilon(scene);
        Image image = Image::rgba(s.width, s.height);
        forEachRow(s, "mesh.pathtrace", [&](int y) {
            enableFastFloatMode();
            PathCounts counts;
            for (int x = 0; x < s.width; ++x) {
                Vec3f sum(0, 0, 0);
                for (int i = 0; i < s.spp; ++i) {
                    const PixelSampler sampler(s.seed, x, y, std::uint32_t(i), std::uint32_t(s.spp));
                    const double jx = jitter_ ? sampler.get(0) : 0.5, jy = jitter_ ? sampler.get(1) : 0.5;
                    const Ray ray = scene.cameraAt(sampler.get(kTimeDim)).generate(x + jx, y + jy, s.width, s.height);
                    const Vec3f d(float(ray.dir.x()), float(ray.dir.y()), float(ray.dir.z()));
                    const Vec3f o(float(ray.origin.x()), float(ray.origin.y()), float(ray.origin.z()));
                    sum += radiance(scene, accel, o, d, sampler, counts);
                }
                float* px = image.pixel(x, y);
                const float inv = 1.0f / float(s.spp);
                px[0] = sum.x() * inv, px[1] = sum.y() * inv, px[2] = sum.z() * inv, px[3] = 1.0f;
            }
            ctx.counters.add("rays.camera", std::int64_t(s.width) * s.spp);
            ctx.counters.add("rays.bounce", counts.bounce);
            ctx.counters.add("rays.shadow", counts.shadow);
        });
        return image;
    }

private:
    static constexpr std::uint32_t kDimsPerVertex = 8;
    static constexpr std::uint32_t kTimeDim = 1u << 24;  // the shutter time: a dimension no path vertex reaches

    Vec3f radiance(const Scene& scene, const MeshAccel& accel, Vec3f o, Vec3f d, const PixelSampler& sampler,
                   PathCounts& counts) const {
        Vec3f L(0, 0, 0), throughput(1, 1, 1);
        for (int depth = 1; depth <= maxDepth_; ++depth) {
            const SurfaceHit hit = accel.intersect(o, d, 0.0f, std::numeric_limits<float>::infinity());
            if (!hit.valid()) break;
            const Vec3f p = o + d * hit.t, wo = -d;
            const Material& mat = scene.materials[accel.material(hit.geom, hit.prim)];
            const bool front = hit.normal.dot(wo) > 0;
            if (depth == 1 && front && mat.emissive()) L += mat.emission;
            const Vec3f n = front ? hit.normal : -hit.normal;
            const Brdf brdf = Brdf::of(mat, model_);
            const std::uint32_t dim = 2 + kDimsPerVertex * std::uint32_t(depth - 1);
            L += throughput * directLight(scene, accel, p, n, wo, brdf, sampler, dim, eps_, counts.shadow);
            if (depth == maxDepth_) break;
            if (depth >= rrDepth_) {
                const float q = std::min(0.95f, std::max({throughput.x(), throughput.y(), throughput.z()}));
                if (sampler.get(dim + 6) >= q) break;
                throughput /= q;
            }
            const Vec3f wi = brdf.sample(wo, n, sampler.get(dim + 3), sampler.get(dim + 4), sampler.get(dim + 5));
            const float cosI = n.dot(wi), pdf = brdf.pdf(wo, wi, n);
            if (cosI <= 0 || !(pdf > 0)) break;
            throughput *= brdf.eval(wo, wi, n) * (cosI / pdf);
            o = p + n * eps_, d = wi;
            ++counts.bounce;
        }
        return L;
    }

    int maxDepth_;
    int rrDepth_;
    bool jitter_;
    GlossyModel model_;
    float eps_ = 1e-5f;
};

const TechniqueRegistrar registrar{{
    "mesh.pathtrace",
    "unbiased path tracing of meshes with next-event estimation (the reference for lighting techniques)",
    ParamTable("mesh.pathtrace",
               {intParam("max_depth", 8, 1, 1024, "surface interactions per path: 1 = direct light, 2 = one indirect bounce"),
                intParam("rr_depth", 3, 1, 1024, "path vertices before Russian roulette may end a path"),
                boolParam("jitter", true, "random positions inside each pixel (antialiasing); false: pixel centres, as a G-buffer sees them"),
                enumParam("glossy", "phong", {"phong", "blinn"}, "glossy lobe of Ks/Ns materials: Phong (mirror direction) or Blinn-Phong (half vector)")}),
    [](const Scene& scene, const ParamSet& p) { return std::make_unique<PathTracer>(scene, p); },
    /*motionBlur=*/true,
    /*renders=*/Content::Meshes,
}};

}  // namespace

}  // namespace weft
