#include "plugins/lighting_vpl_deferred/shading.hpp"

#include <tbb/parallel_for.h>

#include <limits>
#include <optional>

#include "core/lighting/delta_lights.hpp"
#include "core/lighting/emitters.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/base/run/progress.hpp"
#include "core/base/rng.hpp"

namespace weft {

namespace {

const Counter kFragmentsShaded{"fragments.shaded", "texel x VPL evaluations of deferred shading"};
const Counter kRaysBiasCompensation{"rays.bias_compensation", "rays traced to compensate the bias of clamped VPL contributions"};

// A square tile of one sub-buffer: the unit of parallel work. Square tiles
// keep the shadow rays from one VPL close together (coherent traversal).
struct ShadeTask {
    int subBuffer, x0, y0, x1, y1;  // texel rectangle inside the sub-buffer
};

constexpr int kShadeTile = 32;
constexpr int kRayBlock = 4;

std::vector<ShadeTask> shadeTasks(const SubBufferLayout& L) {
    std::vector<ShadeTask> tasks;
    for (int s = 0; s < L.count(); ++s) {
        const int w = L.subWidth(s % L.n()), h = L.subHeight(s / L.n());
        for (int y = 0; y < h; y += kShadeTile)
            for (int x = 0; x < w; x += kShadeTile)
                tasks.push_back({s, x, y, std::min(w, x + kShadeTile), std::min(h, y + kShadeTile)});
    }
    return tasks;
}

struct TaskCounts {
    std::int64_t fragments = 0, rays = 0;
};

// Where sub-buffer texel (x, y) of the task's sub-buffer lies: in the split
// copy (split order) or, fused, in the G-buffer itself (image order, pixel
// (x n + i, y m + j)). The light buffer is written at the same index.
std::size_t texelIndex(const ShadeSource& src, const SubBufferLayout& L, int i, int j, int x, int y) {
    if (src.split) return std::size_t(L.y0(j) + y) * L.width() + std::size_t(L.x0(i) + x);
    return std::size_t(y * L.m() + j) * L.width() + std::size_t(x * L.n() + i);
}

void shadeTask(const Scene& scene, const ShadeSource& src, const SubBufferLayout& L, const ShadeTask& task,
               const std::vector<const Vpl*>& subset, float subsetPaths, const std::vector<Brdf>& brdfs,
               const ShadeConfig& cfg, LightBuffer& out, TaskCounts& counts, Counters& counters) {
    const int i = task.subBuffer % L.n(), j = task.subBuffer / L.n();
    // The tile's texels, copied once: every VPL of the subset reads them again.
    // In 4x4 blocks: Embree packs a coherent stream 16 rays at a time, and a
    // block's rays leave a VPL in closer directions than a row's.
    std::vector<std::size_t> index;
    std::vector<ShadeTexel> texels;
    for (int by = task.y0; by < task.y1; by += kRayBlock)
        for (int bx = task.x0; bx < task.x1; bx += kRayBlock)
            for (int r = by; r < std::min(task.y1, by + kRayBlock); ++r)
                for (int x = bx; x < std::min(task.x1, bx + kRayBlock); ++x) {
                    const std::size_t o = texelIndex(src, L, i, j, x, r);
                    const ShadeTexel t = src.split ? (*src.split)[o] : ShadeTexel(src.gbuffer->texels[o]);
                    if (!t.background()) index.push_back(o), texels.push_back(t);
                }
    std::vector<VplShading> shading(texels.size());
    std::vector<LightTexel> light(texels.size(), LightTexel{});
    std::vector<RTCRay> rays;
    std::vector<std::uint32_t> lit;
    const MeshAccel& accel = scene.accel();
    std::optional<SegmentAttenuation> attenuation;
    if (cfg.volumes && cfg.visibility) attenuation.emplace(*cfg.volumes);
    SegmentAttenuation* media = attenuation ? &*attenuation : nullptr;
    for (const Vpl* vpl : subset) {
        rays.clear(), lit.clear();
        const Vec3f origin = vpl->position + vpl->normal * cfg.eps;
        for (std::uint32_t k = 0; k < texels.size(); ++k) {
            const ShadeTexel& t = texels[k];
            if (!shadeWithVpl(*vpl, t, cfg.eye, brdfs, cfg.gmax, shading[k])) continue;
            lit.push_back(k);
            if (!cfg.visibility) continue;
            rays.emplace_back();
            // Ends just short of the texel, so texels on an edge are not shadowed by the neighbouring face.
            setRay(rays.back(), origin, t.position + t.normal * cfg.eps - origin, 0.0f, 1.0f - 1e-4f);
        }
        counts.fragments += std::int64_t(texels.size());
        if (cfg.visibility && !rays.empty()) {
            accel.occludedStream(rays.data(), unsigned(rays.size()), true);
            counts.rays += std::int64_t(rays.size());
        }
        const bool emitter = vpl->kind == VplKind::Emitter;
        for (std::size_t r = 0; r < lit.size(); ++r) {
            if (cfg.visibility && rays[r].tfar < 0) continue;  // occluded: Embree set tfar to -inf
            const VplShading& sh = shading[lit[r]];
            LightTexel& o = light[lit[r]];
            if (media) {
                const Vec3f T = media->along(origin, -sh.toLight, sh.distance);
                (emitter ? o.directD : o.indirectD) += sh.d * T;
                (emitter ? o.directS : o.indirectS) += sh.s * T;
                continue;
            }
            (emitter ? o.directD : o.indirectD) += sh.d;
            (emitter ? o.directS : o.indirectS) += sh.s;
        }
    }
    const float scale = 1.0f / subsetPaths;
    for (std::size_t k = 0; k < texels.size(); ++k) {
        const LightTexel& t = light[k];
        out[index[k]] = {t.directD * scale, t.indirectD * scale, t.directS * scale, t.indirectS * scale};
    }
    if (media) media->report(counters);
}

}  // namespace

LightBuffer shadeSubBuffers(const Scene& scene, const ShadeSource& src, const SubBufferLayout& L,
                                        const VplSet& vpls, const std::vector<Brdf>& brdfs, const ShadeConfig& cfg,
                                        Counters& counters, RenderMonitor* monitor) {
    const int S = L.count();
    std::vector<std::vector<const Vpl*>> subsets(static_cast<std::size_t>(S));
    for (const Vpl& v : vpls.vpls) subsets[v.path % std::uint32_t(S)].push_back(&v);
    LightBuffer out = zeroedBuffer<LightTexel>(std::size_t(L.width()) * std::size_t(L.height()));
    const std::vector<ShadeTask> tasks = shadeTasks(L);
    Progress progress("lighting.vpl_deferred shading", std::int64_t(tasks.size()), monitor);
    tbb::parallel_for(std::size_t(0), tasks.size(), [&](std::size_t k) {
        enableFastFloatMode();
        const ShadeTask& task = tasks[k];
        const float paths = float((vpls.paths - std::uint32_t(task.subBuffer) + std::uint32_t(S) - 1) / std::uint32_t(S));
        TaskCounts counts;
        shadeTask(scene, src, L, task, subsets[std::size_t(task.subBuffer)], std::max(1.0f, paths), brdfs, cfg, out, counts, counters);
        counters.add(kFragmentsShaded, counts.fragments);
        counters.add(kRaysShadow, counts.rays);
        progress.advance();
    });
    progress.finish();
    return out;
}

void directLightAt(const Scene& scene, const GTexel& t, const Vec3f& wo, const Brdf& brdf, float eps, const float* u,
                   bool useEmitters, Vec3f& d, Vec3f& s, std::int64_t& rays, SegmentAttenuation* media) {
    const MeshAccel& accel = scene.accel();
    const Vec3f origin = t.position + t.normal * eps;
    auto add = [&](const Vec3f& wi, const Vec3f& radianceCos) {
        d += radianceCos * float(1 / M_PI);
        if (brdf.glossy()) s += radianceCos * brdf.lobe(wo, wi, t.normal);
    };
    auto through = [&](const Vec3f& o, const Vec3f& dir, float dist, const Vec3f& light) {
        return media ? light * media->along(o, dir, dist) : light;
    };
    const Emitters& emitters = scene.emitters();
    if (useEmitters && !emitters.empty()) {
        const EmitterSample e = emitters.sample(u[0], u[1], u[2]);
        const EmitterView v = viewFrom(e, origin);
        const Vec3f& to = v.wi;
        const float dist = v.distance, d2 = v.distance2, cosX = t.normal.dot(to), cosL = v.cosLight;
        if (cosX > 0 && cosL > 0) {
            ++rays;
            if (!accel.occluded(origin, to, eps, dist * (1.0f - 1e-4f)))
                add(to, through(origin, to, dist, e.radiance * (cosX * cosL / (d2 * e.pdfArea))));
        }
    }
    for (const Light& light : scene.lights) {
        const DeltaIllumination li = illuminate(light, origin);
        const float cosX = t.normal.dot(li.wi);
        if (cosX <= 0) continue;
        ++rays;
        if (!accel.occluded(origin, li.wi, eps, li.distance * (1.0f - 1e-4f))) add(li.wi, through(origin, li.wi, li.distance, li.irradiance * cosX));
    }
}

void compensateClamping(const Scene& scene, const GBuffer& g, const std::vector<Brdf>& brdfs, const ShadeConfig& cfg,
                        int samples, std::uint64_t seed, LightBuffer& light, Counters& counters) {
    const MeshAccel& accel = scene.accel();
    const float reach = 1.0f / std::sqrt(cfg.gmax);
    // A BRDF-sampled ray of a pixel, waiting in its row's stream.
    struct Bounce {
        int x, sample;
        Vec3f wi;
        float cosX, pdf;
    };
    tbb::parallel_for(0, g.height, [&](int y) {
        enableFastFloatMode();
        std::int64_t rays = 0;
        std::optional<SegmentAttenuation> attenuation;
        if (cfg.volumes) attenuation.emplace(*cfg.volumes);
        SegmentAttenuation* media = attenuation ? &*attenuation : nullptr;
        auto u = [&](int x, int i, std::uint32_t dim) { return pixelRandom(seed ^ 0x6b6b6b6bull, x, y, std::uint32_t(i), dim); };
        // The row's rays go to Embree as one stream, in pixel and sample order.
        std::vector<Bounce> bounces;
        std::vector<RTCRayHit> stream;
        for (int x = 0; x < g.width; ++x) {
            const GTexel& t = g.at(x, y);
            if (t.background()) continue;
            const Brdf& fx = brdfs[std::size_t(t.material)];
            const Vec3f wo = (cfg.eye - t.position).unitSafe();
            for (int i = 0; i < samples; ++i) {
                const Vec3f wi = fx.sample(wo, t.normal, u(x, i, 0), u(x, i, 1), u(x, i, 2));
                const float cosX = t.normal.dot(wi), pdf = fx.pdf(wo, wi, t.normal);
                if (cosX <= 0 || !(pdf > 0)) continue;
                // G = cosX cosY / d^2 <= 1 / d^2 exceeds gmax only closer than 1 / sqrt(gmax): farther hits add nothing.
                bounces.push_back({x, i, wi, cosX, pdf});
                stream.emplace_back();
                setRay(stream.back().ray, t.position + t.normal * cfg.eps, wi, 0.0f, reach);
                stream.back().hit.geomID = RTC_INVALID_GEOMETRY_ID;
            }
        }
        rays += std::int64_t(stream.size());
        if (!stream.empty()) accel.intersectStream(stream.data(), unsigned(stream.size()), false);
        for (std::size_t k = 0; k < bounces.size(); ++k) {
            const RTCRayHit& rh = stream[k];
            if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
            const Bounce& b = bounces[k];
            const GTexel& t = g.at(b.x, y);
            const Brdf& fx = brdfs[std::size_t(t.material)];
            const Vec3f wo = (cfg.eye - t.position).unitSafe(), normal = accel.normal(rh.hit.geomID, rh.hit.primID);
            const float tHit = rh.ray.tfar, cosY = std::abs(normal.dot(b.wi));
            const float G = b.cosX * cosY / (tHit * tHit);
            if (G <= cfg.gmax) continue;
            // Light leaving y towards x: its direct light, reflected by its BRDF.
            GTexel ty;
            ty.position = t.position + t.normal * cfg.eps + b.wi * tHit;
            ty.normal = normal.dot(b.wi) < 0 ? normal : -normal;
            ty.material = std::int32_t(accel.material(rh.hit.geomID, rh.hit.primID));
            const Brdf& fy = brdfs[std::size_t(ty.material)];
            const float lu[3] = {u(b.x, b.sample, 3), u(b.x, b.sample, 4), u(b.x, b.sample, 5)};
            Vec3f dY(0, 0, 0), sY(0, 0, 0);
            directLightAt(scene, ty, -b.wi, fy, cfg.eps, lu, true, dY, sY, rays, media);
            Vec3f leaving = fy.kd * dY + fy.ks * sY;
            if (media) leaving *= media->along(t.position + t.normal * cfg.eps, b.wi, tHit);
            const Vec3f radiance = leaving * ((1.0f - cfg.gmax / G) * b.cosX / (b.pdf * float(samples)));
            LightTexel& out = light[std::size_t(y) * g.width + b.x];
            out.indirectD += radiance * float(1 / M_PI);
            if (fx.glossy()) out.indirectS += radiance * fx.lobe(wo, b.wi, t.normal);
        }
        counters.add(kRaysBiasCompensation, rays);
        if (media) media->report(counters);
    });
}

}  // namespace weft
