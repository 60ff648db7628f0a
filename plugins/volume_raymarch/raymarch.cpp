// volume.raymarch — emission-absorption ray marching at a fixed step, through
// every volume of the scene and up to the first surface.
//
// Each camera ray is clipped to each volume's index box and sampled every
// `step` voxel lengths with trilinear interpolation (OpenVDB BoxSampler);
// each sample's transfer-function colour and extinction make a segment of
// opacity 1 - exp(-extinction * step), composited front to back. With a very
// small step this is the reference other volume techniques are measured
// against. Several volumes: the step is in voxel lengths of the finest
// volume the ray crosses, and where volumes overlap their extinctions and
// emissions add (volume_march.hpp states the rule).
//
// Motion blur: each camera sample's shutter time moves the camera along its
// keys and the volumes along their velocity (volume_march.hpp).
//
// Meshes: a ray ends at its first surface (Embree); the last segment is cut
// there and integrated with its true length. The surface is lit by the
// scene's point and directional lights and emissive triangles with shadow
// rays against the meshes (Lambert + Phong, core/lighting/brdf.hpp), adds its
// own emission where seen from the front, and is composited behind the
// volumes: colour = volume + transmittance x surface, alpha 1. The
// emission-absorption volumes do not shadow the surfaces (their light is
// their own emission, not scattered light).
//
// Parameters (see `weft help volume.raymarch`):
//   step        distance between samples, in voxel lengths (the speed/accuracy knob)
//   jitter      random offset of the first sample per ray (banding -> noise)
//   ert         early ray termination once opacity reaches this (1 = off)
//   skip_empty  skip the cells the transfer function shows nothing of
//               (core/volume/skip/visible_cells.hpp: min-max space leaping on the
//               grid's own leaves, OpenVDB HDDA on each grid's index space,
//               so any affine transform works); the image is unchanged, only
//               fewer samples are taken. auto (the default) skips where it
//               pays (emptySpacePays, volume_march.hpp); the skipper is
//               built once per process for the same volumes
//               (sharedEmptySpaceSkipper); with a still camera, rays
//               outside the visible blocks' screen footprint skip the
//               march (core/volume/skip/screen_footprint.hpp)
//   offset_pattern  per-pixel offsets of the first sample from a pattern set's
//               third coordinate: interleaved:4x4 gives the 16 pixels of each
//               tile 16 different strata of the step (Keller & Heidrich 4.3)
//   pattern, filter, adaptive...  image-plane sampling and reconstruction
//               (core/sampling/image_plane.hpp)
//
// Counters: rays.camera, volume.samples (trilinear lookups of the grids);
// with meshes also rays.surface (camera rays ending at a surface) and
// rays.shadow.
#include <limits>
#include <optional>

#include "core/base/rng.hpp"
#include "core/sampling/image_plane.hpp"
#include "core/lighting/delta_lights.hpp"
#include "core/lighting/surface_shading.hpp"
#include "plugins/volume_raymarch/volume_march.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

struct RaymarchParams {
    double step;
    bool jitter;
    float ertOpacity;
    std::string offsetPattern;
};

std::vector<ParamSpec> raymarchParams() {
    std::vector<ParamSpec> specs = {
        floatParam("step", 0.5, 1e-4, 64, "distance between samples along a ray, in voxel lengths of the finest volume it crosses"),
        boolParam("jitter", false, "random per-ray offset of the first sample (trades banding for noise)"),
        floatParam("ert", 0.99, 0, 1, "early ray termination once opacity reaches this (1 = never)"),
        enumParam("skip_empty", "auto", {"auto", "true", "false"},
                  "skip cells whose values the transfer function shows nothing of (min-max space leaping over 8^3 blocks, "
                  "OpenVDB HDDA where the grid spreads wide or moves); same "
                  "image, fewer samples. auto: where the cells left fill at most 3/4 of the active box"),
        stringParam("offset_pattern", "", "offset of the first sample per pixel from a pattern set's third coordinate, "
                                          "e.g. interleaved:4x4,basis=jittered (Keller & Heidrich 4.3); empty: jitter or centre",
                    [](const std::string& v) { if (!v.empty()) validatePatternSpec(v); }),
    };
    return withImagePlaneParams(std::move(specs), PlainSamples::Jittered);
}

// Per-pixel-sample counts of one row's shader.
struct RaymarchCounts {
    std::int64_t rays = 0, surface = 0, shadow = 0;
};

class Raymarch final : public Technique {
public:
    Raymarch(const Scene& scene, const ParamSet& p)
        : params_{p.getFloat("step"), p.getBool("jitter"), float(p.getFloat("ert")), p.getString("offset_pattern")},
          plane_(readImagePlaneOptions(p, PlainSamples::Jittered)) {
        if (params_.jitter && !params_.offsetPattern.empty())
            throw Error("volume.raymarch: jitter=true and offset_pattern both set the first sample's offset; choose one");
        const std::string& skip = p.getString("skip_empty");
        for (const Volume& vol : scene.volumes)
            if (skip == "true" && vol.tf.lookup(vol.grid->background()).extinction > 0)
                throw Error("volume.raymarch: skip_empty=true needs a transfer function that is transparent at the grid's background value "
                            "(volume '" + vol.source + "')");
        requireSurfaceLights(scene, "volume.raymarch");
        if (!scene.volumes.empty() && (skip == "true" || (skip == "auto" && emptySpaceSkippable(scene.volumes)))) {
            skipper_ = sharedEmptySpaceSkipper(scene.volumes).skipper;
            if (skip == "auto" && !skipper_->pays()) skipper_.reset();
        }
        // A full march of a dense grid reads it from one array; a skipping
        // one looks up too few cells for the copy to pay.
        if (!skipper_)
            for (const Volume& vol : scene.volumes) dense_.push_back(DenseCopy<openvdb::FloatGrid>::of(*vol.grid));
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        std::optional<PatternSet> offsets;
        if (!params_.offsetPattern.empty()) offsets = makePatternSet(params_.offsetPattern, s.spp, hashCombine(s.seed, 0x0ff5));
        const MeshAccel* accel = scene.meshes.empty() ? nullptr : &scene.accel();  // built before the pixel loop
        if (accel) scene.emitters();
        const float eps = accel ? rayEpsilon(scene) : 0.0f;
        const ImagePlane plane(plane_, s);
        const VolumeBvh bounds = scene.volumes.size() > 1 ? VolumeBvh::of(scene.volumes) : VolumeBvh();
        MarchSettings march{params_.step, params_.ertOpacity, scene.volumes.size() > 1 ? &bounds : nullptr, {}};
        for (const auto& d : dense_) march.dense.push_back(d.get());
        const std::optional<CameraRays> still = scene.stillCameraRays(s.width, s.height);  // the camera's frame, where it holds all frame long
        const std::optional<ScreenFootprint> footprint = footprintOf(scene, still, s);
        // One per row: its own grid accessors and HDDAs, and its counts.
        struct Shader {
            const Raymarch& self;
            const Scene& scene;
            const RenderSettings& s;
            const std::optional<PatternSet>& offsets;
            const MeshAccel* accel;
            float eps;
            const std::optional<ScreenFootprint>& footprint;
            VolumeMarcher marcher;  // built in place, never copied
            const std::optional<CameraRays>& rays;
            RaymarchCounts counts;

            Shader(const Raymarch& r, const Scene& sc, const RenderSettings& st, const std::optional<PatternSet>& o,
                   const MeshAccel* a, float e, const std::optional<ScreenFootprint>& f, const MarchSettings& m,
                   const std::optional<CameraRays>& still)
                : self(r), scene(sc), s(st), offsets(o), accel(a), eps(e), footprint(f), marcher(sc, m, r.skipper_.get()), rays(still) {}
            Rgba operator()(const CameraSample& c) {
                const Ray ray = rays ? rays->at(c.x, c.y) : scene.cameraAt(c.time).generate(c.x, c.y, s.width, s.height);
                float offset = self.params_.jitter ? pixelRandom(s.seed, c.px, c.py, c.index, 0) : 0.5f;
                if (offsets) offset = offsets->sample(c.px, c.py, int(c.index % std::uint32_t(s.spp))).t;
                ++counts.rays;
                const SurfaceHit hit = accel ? firstSurface(*accel, ray) : SurfaceHit{};
                const double tSurface = hit.valid() ? double(hit.t) : std::numeric_limits<double>::infinity();
                double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
                if (footprint) footprint->rayRange(c.x, c.y, ray.dir, t0, t1);  // t0 > t1: the march would find nothing
                const RayAccumulator acc = t0 <= t1 ? marcher.march(ray, tSurface, offset, scene.shutter.frameTime(0, c.time), t0, t1)
                                                    : RayAccumulator{};
                if (!hit.valid()) return {acc.r, acc.g, acc.b, acc.opacity()};
                ++counts.surface;
                const PixelSampler sampler(s.seed, c.px, c.py, c.index, std::uint32_t(s.spp));
                const Vec3f L = shadeSurface(scene, *accel, ray, hit, sampler, eps, counts.shadow);
                const float T = acc.transmittance;
                return {acc.r + T * L.x(), acc.g + T * L.y(), acc.b + T * L.z(), 1.0f};
            }
            void flush(Counters& counters) const {
                counters.add(kRaysCamera, counts.rays);
                counters.add(kVolumeSamples, marcher.samples());
                if (!accel) return;  // mesh-free renders keep their counters as they were
                counters.add(kRaysSurface, counts.surface);
                counters.add(kRaysShadow, counts.shadow);
            }
        };
        return plane.render(ctx, "volume.raymarch", [&] { return Shader(*this, scene, s, offsets, accel, eps, footprint, march, still); });
    }

    // With the skipper's blocks and a still camera, the pixels whose rays
    // can reach a visible cell; the others skip the march.
    std::optional<ScreenFootprint> footprintOf(const Scene& scene, const std::optional<CameraRays>& still, const RenderSettings& s) const {
        if (!skipper_ || !still) return std::nullopt;
        return skipper_->footprint(scene.volumes, *still, s.width, s.height);
    }

private:
    RaymarchParams params_;
    ImagePlaneOptions plane_;
    std::shared_ptr<const EmptySpaceSkipper> skipper_;  // shared with the process's other renders of these volumes
    std::vector<std::unique_ptr<const DenseCopy<openvdb::FloatGrid>>> dense_;  // per volume; null where sparse
};

const TechniqueRegistrar registrar{{
    "volume.raymarch",
    "emission-absorption ray marching at a fixed step (the reference volume renderer)",
    ParamTable("volume.raymarch", raymarchParams()),
    [](const Scene& scene, const ParamSet& p) { return std::make_unique<Raymarch>(scene, p); },
    /*motionBlur=*/true,
    /*renders=*/Content::VolumesAndMeshes,
    /*bytesPerPixel=*/32,
    /*reference=*/{"volume.raymarch", {"step=0.1"}, 256},
    /*knobs=*/{{"step", {"2", "1", "0.5", "0.25", "0.125"}}, {"spp", {"1", "4", "16", "64"}}},
    /*scatters=*/false,
    /*velocityBlur=*/false,
    /*emission=*/true,
}};

}  // namespace

}  // namespace weft
