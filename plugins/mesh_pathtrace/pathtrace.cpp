// mesh.pathtrace — unbiased path tracing of meshes and volumes together,
// the reference the VPL and the volume techniques are measured against.
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
// In scenes with volumes the path tracer is volumetric (core/volume/media/medium.hpp):
// free flights by weighted delta tracking against the max-channel majorant
// (each RGB channel unbiased), Henyey-Greenstein scattering, and next-event
// estimation at medium and surface vertices whose shadow rays surfaces block
// and volumes attenuate (delta or ratio tracking, `shadow_tracking`). Every
// scattering event, in a medium or on a surface, is a path vertex. Camera
// rays that leave the scene carry alpha = 1 - their transmittance; a surface
// gives alpha 1. Tracking draws from a per-sample generator (a pure function
// of seed, pixel and sample), so mesh-only scenes use the sampler exactly as
// before and render the same image.
//
// Parameters (see `weft help mesh.pathtrace`):
//   max_depth  scattering events (surface or medium) per path: 1 = direct
//              light only (single scattering), 2 = plus one indirect bounce
//              (the VPL techniques' one bounce)
//   rr_depth   vertices before Russian roulette starts
//   glossy     phong | blinn: the glossy lobe of materials with Ks
//   jitter     sample positions inside the pixel; false shoots every sample
//              through the pixel centre, the way G-buffer techniques see it
//   pattern, filter, adaptive...  image-plane sampling and reconstruction
//              (core/sampling/image_plane.hpp): a camera sample gives the
//              ray's position and shutter time, the path's other dimensions
//              still come from the sampler of (pixel, sample index). With
//              no pattern the plane's positions are the sampler's
//              dimensions 0 and 1 (jitter) or pixel centres, as before.
//   shadow_tracking  delta | ratio: the transmittance estimator of shadow
//              rays through volumes
//
// Velocity motion blur: every vertex and shadow ray of a camera sample's
// path sees the moving volumes at that sample's shutter time
// (core/volume/media/medium.hpp); the camera moves along its keys as well.
//
// Counters: rays.camera, image.samples, rays.bounce, rays.shadow; with volumes also
// volume.lookups (density reads) and volume.collisions (tentative
// collisions of free flights and shadow rays).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/lighting/brdf.hpp"
#include "core/lighting/delta_lights.hpp"
#include "core/lighting/direct_light.hpp"
#include "core/lighting/emitters.hpp"
#include "core/lighting/medium_light.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/sampling/image_plane.hpp"
#include "core/sampling/pixel_sampler.hpp"
#include "core/volume/media/medium.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

const Counter kRaysBounce{"rays.bounce", "path continuation rays after a bounce"};
const Counter kVolumeCollisions{"volume.collisions", "tentative collisions of free flights and shadow rays"};

struct PathCounts {
    std::int64_t bounce = 0, shadow = 0;
};

// Per-row state of volumetric paths: a medium ray for free flights and the
// shadow rays (their OpenVDB accessors belong to one thread).
struct MediumRow {
    MediumRow(const MeshAccel& accel, const Medium& medium, ShadowTracking tracking)
        : flight(medium), shadow(accel, medium, tracking) {}
    MediumRay flight;
    ShadowRays shadow;
    std::int64_t collisions = 0;
};

// What a camera sample brings: radiance and coverage.
struct PathSample {
    Vec3f L{0, 0, 0};
    float alpha = 1;
};

ShadowTracking shadowTrackingNamed(const std::string& name) {
    return name == "ratio" ? ShadowTracking::Ratio : ShadowTracking::Delta;
}

// Meshes keep their light rules; a volume-only scene needs a point or
// directional light unless a volume emits.
void requireLights(const Scene& scene) {
    if (!scene.meshes.empty() || scene.volumes.empty()) return requireMeshLights(scene, "mesh.pathtrace");
    for (const Light& l : scene.lights)
        if (l.type == LightType::Environment) throw Error("mesh.pathtrace does not support environment lights (use point, directional or emissive materials)");
    const bool glows = std::any_of(scene.volumes.begin(), scene.volumes.end(), [](const Volume& v) { return bool(v.emission); });
    if (scene.lights.empty() && !glows)
        throw Error("mesh.pathtrace: the scene '" + scene.source + "' has volumes but no light (add a point or directional light)");
}

// jitter chooses the plain default: the stratified sampler's positions, or
// pixel centres (a pattern or adaptive sampling would override it).
ImagePlaneOptions planeOptions(const ParamSet& p) {
    ImagePlaneOptions o = readImagePlaneOptions(p);
    o.plain = p.getBool("jitter") ? PlainSamples::Stratified : PlainSamples::Centres;
    if (o.plain == PlainSamples::Centres && (!o.pattern.empty() || o.adaptive != AdaptiveMode::Off))
        throw Error("mesh.pathtrace: jitter=false shoots pixel centres, but pattern/adaptive place the samples; choose one");
    return o;
}

std::vector<ParamSpec> pathtraceParams() {
    std::vector<ParamSpec> specs = {
        intParam("max_depth", 8, 1, 1024, "scattering events (surface or medium) per path: 1 = direct light (single scattering), 2 = one indirect bounce"),
        intParam("rr_depth", 3, 1, 1024, "path vertices before Russian roulette may end a path"),
        boolParam("jitter", true, "without a pattern: stratified random positions inside each pixel (antialiasing); "
                                  "false: pixel centres at every spp, as a G-buffer sees them (not with pattern/adaptive)"),
        enumParam("glossy", "phong", {"phong", "blinn"}, "glossy lobe of Ks/Ns materials: Phong (mirror direction) or Blinn-Phong (half vector)"),
        enumParam("shadow_tracking", "ratio", {"ratio", "delta"}, "transmittance of shadow rays through volumes: ratio tracking (smooth) or delta tracking (binary)"),
    };
    return withImagePlaneParams(std::move(specs), PlainSamples::Stratified);
}

bool finite(const Vec3f& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }
double maxChannel(const Vec3d& v) { return std::max({v[0], v[1], v[2]}); }

class PathTracer final : public Technique {
public:
    PathTracer(const Scene& scene, const ParamSet& p)
        : maxDepth_(int(p.getInt("max_depth"))), rrDepth_(int(p.getInt("rr_depth"))), plane_(planeOptions(p)),
          model_(Brdf::modelNamed(p.getString("glossy"))), tracking_(shadowTrackingNamed(p.getString("shadow_tracking"))) {
        requireLights(scene);
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        // Built before the pixel loop; a volume-only scene traces an empty
        // BVH, made only then (an Embree device and commit cost ~2 ms).
        std::optional<MeshAccel> noMeshes;
        if (scene.meshes.empty()) noMeshes.emplace(std::vector<TriangleMesh>{});
        const Emitters noEmitters;
        const MeshAccel& accel = noMeshes ? *noMeshes : scene.accel();
        emitters_ = scene.meshes.empty() ? &noEmitters : &scene.emitters();
        eps_ = rayEpsilon(scene);
        const Medium medium(scene.volumes);
        const ImagePlane plane(plane_, s);
        return plane.render(ctx, "mesh.pathtrace", [&] { return Shader(*this, scene, accel, medium, s); });
    }

private:
    // One per row (made on the thread that renders it): the row's medium
    // rays and counts. A camera sample gives the ray's position and time;
    // the path's other dimensions come from the PixelSampler and generator
    // of (pixel, sample index), as they did before the image plane.
    struct Shader {
        const PathTracer& self;
        const Scene& scene;
        const MeshAccel& accel;
        const RenderSettings& s;
        std::optional<MediumRow> row;  // built in place, never copied
        PathCounts counts;
        std::int64_t cameraRays = 0;

        Shader(const PathTracer& t, const Scene& sc, const MeshAccel& a, const Medium& medium, const RenderSettings& st)
            : self(t), scene(sc), accel(a), s(st) {
            enableFastFloatMode();
            if (!medium.empty()) row.emplace(accel, medium, self.tracking_);
        }
        Rgba operator()(const CameraSample& c) {
            const PixelSampler sampler(s.seed, c.px, c.py, c.index, std::uint32_t(s.spp));
            const Ray ray = scene.cameraAt(c.time).generate(c.x, c.y, s.width, s.height);
            const Vec3f d = toVec3f(ray.dir), o = toVec3f(ray.origin);
            ++cameraRays;
            if (!row) {
                const Vec3f L = self.radiance(scene, accel, o, d, sampler, counts);
                // Volumes that are all empty (an empty frame) still composite: alpha 0 where no surface is seen.
                const bool opaque = scene.volumes.empty() || accel.intersect(o, d, 0.0f, std::numeric_limits<float>::infinity()).valid();
                return {L.x(), L.y(), L.z(), opaque ? 1.0f : 0.0f};
            }
            const double time = scene.shutter.frameTime(0, c.time);  // moving volumes: the free flights' and shadow rays' time
            row->flight.setTime(time);
            row->shadow.setTime(time);
            Rng rng(hashCombine(hashCombine(s.seed ^ kMediumStream, (std::uint64_t(std::uint32_t(c.px)) << 32) | std::uint32_t(c.py)),
                                std::uint64_t(c.index)));
            const PathSample p = self.radianceThroughMedia(scene, accel, o, d, sampler, rng, *row, counts);
            return {p.L.x(), p.L.y(), p.L.z(), p.alpha};
        }
        void flush(Counters& counters) const {
            counters.add(kRaysCamera, cameraRays);
            counters.add(kRaysBounce, counts.bounce);
            counters.add(kRaysShadow, counts.shadow + (row ? row->shadow.traced : 0));
            if (!row) return;
            counters.add(kVolumeLookups, row->flight.lookups + row->shadow.lookups());
            counters.add(kVolumeCollisions, row->collisions + row->shadow.collisions);
        }
    };

    static constexpr std::uint32_t kDimsPerVertex = 8;
    static constexpr std::uint64_t kMediumStream = 0x6d656469756dull;  // keys the tracking generator

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

    // A path through volumes and surfaces. Each segment runs from o to the
    // first surface; a free flight inside it either scatters in a medium or
    // reaches the surface (or leaves the scene) with its null-collision weights.
    PathSample radianceThroughMedia(const Scene& scene, const MeshAccel& accel, Vec3f o, Vec3f d,
                                    const PixelSampler& sampler, Rng& rng, MediumRow& row, PathCounts& counts) const {
        PathSample out;
        Vec3d beta(1.0);
        for (int vertex = 1;; ++vertex) {
            const SurfaceHit hit = accel.intersect(o, d, 0.0f, std::numeric_limits<float>::infinity());
            row.flight.reset(toVec3d(o), toVec3d(d), hit.valid() ? double(hit.t) : std::numeric_limits<double>::infinity());
            const FreeFlight flight = row.flight.empty() ? FreeFlight{} : sampleFreeFlight(row.flight, rng, beta, row.collisions);
            out.L += toVec3f(flight.emitted);
            if (vertex == 1 && !hit.valid() && !flight.scattered)  // E[beta] = transmittance per channel
                out.alpha = std::clamp(1.0f - float((beta[0] + beta[1] + beta[2]) / 3.0), 0.0f, 1.0f);
            if (!(maxChannel(beta) > 0) || (!flight.scattered && !hit.valid())) break;
            const std::uint32_t dim = 2 + kDimsPerVertex * std::uint32_t(vertex - 1);
            Vec3f wi;
            if (flight.scattered) {
                const Vec3f p = o + d * float(flight.t);
                const double g = flight.coefficients.g;
                auto phase = [&](const Vec3f& w) { const float f = float(henyeyGreenstein(g, double(d.dot(w)))); return Vec3f(f, f, f); };
                out.L += toVec3f(beta) * directLightThroughMedia(scene, *emitters_, p, phase, sampler.get(dim), sampler.get(dim + 1), sampler.get(dim + 2), eps_, row.shadow, rng);
                if (vertex == maxDepth_ || !survives(beta, vertex, sampler.get(dim + 6))) break;
                wi = toVec3f(sampleHenyeyGreenstein(toVec3d(d), g, sampler.get(dim + 3), sampler.get(dim + 4)));  // weight 1: pdf = phase
                o = p;
            } else {
                const Vec3f p = o + d * hit.t, wo = -d;
                const Material& mat = scene.materials[accel.material(hit.geom, hit.prim)];
                const bool front = hit.normal.dot(wo) > 0;
                if (vertex == 1 && front && mat.emissive()) out.L += toVec3f(beta) * mat.emission;
                const Vec3f n = front ? hit.normal : -hit.normal;
                const Brdf brdf = Brdf::of(mat, model_);
                auto reflect = [&](const Vec3f& w) { const float c = n.dot(w); return c > 0 ? brdf.eval(wo, w, n) * c : Vec3f(0, 0, 0); };
                out.L += toVec3f(beta) * directLightThroughMedia(scene, *emitters_, p + n * eps_, reflect, sampler.get(dim), sampler.get(dim + 1), sampler.get(dim + 2), eps_, row.shadow, rng);
                if (vertex == maxDepth_ || !survives(beta, vertex, sampler.get(dim + 6))) break;
                wi = brdf.sample(wo, n, sampler.get(dim + 3), sampler.get(dim + 4), sampler.get(dim + 5));
                const float cosI = n.dot(wi), pdf = brdf.pdf(wo, wi, n);
                if (cosI <= 0 || !(pdf > 0)) break;
                beta *= toVec3d(brdf.eval(wo, wi, n) * (cosI / pdf));
                o = p + n * eps_;
            }
            d = wi;
            ++counts.bounce;
        }
        if (!finite(out.L)) out.L = Vec3f(0, 0, 0);  // a degenerate sample must not poison the pixel
        return out;
    }

    // Russian roulette after rr_depth vertices; survivors carry 1/q.
    bool survives(Vec3d& beta, int vertex, float u) const {
        if (vertex < rrDepth_) return true;
        const double q = std::min(0.95, maxChannel(beta));
        if (u >= q) return false;
        beta /= q;
        return true;
    }

    int maxDepth_;
    int rrDepth_;
    ImagePlaneOptions plane_;
    GlossyModel model_;
    ShadowTracking tracking_;
    float eps_ = 1e-5f;
    const Emitters* emitters_ = nullptr;  // during render()
};

const TechniqueRegistrar registrar{{
    "mesh.pathtrace",
    "unbiased volumetric path tracing of meshes and volumes with next-event estimation (the reference for every technique)",
    ParamTable("mesh.pathtrace", pathtraceParams()),
    [](const Scene& scene, const ParamSet& p) { return std::make_unique<PathTracer>(scene, p); },
    /*motionBlur=*/true,
    /*renders=*/Content::VolumesAndMeshes,
    /*bytesPerPixel=*/32,
    /*reference=*/{"mesh.pathtrace", {}, 4096},
    /*knobs=*/{{"spp", {"1", "4", "16", "64", "256"}}},
    /*scatters=*/true,
    /*velocityBlur=*/false,
    /*emission=*/true,
}};

}  // namespace

}  // namespace weft
