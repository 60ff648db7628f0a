// volume.singlescatter — single scattering in a density grid, lit by
// directional, point and emissive-triangle lights, with vdb_render's model
// and parameter names (or, physical=true, the path tracer's conventions).
//
// A primary ray gathers, at each sample with density rho >= cutoff,
//   light * albedo * phase * T_shadow * T_primary * (1 - exp(-sigma_t rho step))
// with sigma_t = absorb + scatter and albedo = scatter / sigma_t per RGB
// channel, as vdb_render's VolumeRender does. What differs is how:
//   estimator=cached   (default) shadow transmittance from a per-light grid
//                      of density-weighted path lengths built once
//                      (light_cache.hpp), so finer primary steps stay cheap;
//   estimator=ratio    unbiased ratio tracking of every shadow ray;
//   estimator=raymarch vdb_render's fixed-step shadow march, and with
//                      jitter off its fixed sample phase: the same integrator.
// weft's estimators offset each pixel's primary samples randomly (jitter),
// which trades vdb_render's concentric rings for noise.
//
// Camera samples come from the image plane (core/sampling/image_plane.hpp:
// pattern, filter, adaptive...); with no pattern, the pixel centre at 1 spp
// and a jittered grid in each pixel beyond (PlainSamples::Jittered).
//
// compat=vdb_render also takes vdb_render's camera options and builds its
// camera (scatter_params.hpp).
//
// Whole scenes (scatter_tracer.hpp): any number of volumes, each with any
// affine grid transform, its coefficients from the scene's medium (else
// absorb/scatter); camera rays end at the first mesh, which the lights
// shade through the meshes and the volumes; meshes shadow the volumes too
// (the cache keeps a visibility grid). step and shadowstep count voxel
// lengths (cube root of a voxel's volume): index units on uniform grids.
//
// Motion blur: each camera sample's shutter time moves the camera along its
// keys and the volumes along their velocity (scatter_tracer.hpp).
//
// Counters: rays.camera, image.samples, volume.samples (density lookups along primary
// rays), shadow.samples (density lookups for shadows, the cache included),
// mesh.shadow_rays (with meshes only).
#include <cmath>
#include <optional>

#include "core/base/rng.hpp"
#include "core/lighting/delta_lights.hpp"
#include "core/lighting/surface_shading.hpp"
#include "core/sampling/image_plane.hpp"
#include "plugins/technique.hpp"
#include "plugins/volume_singlescatter/scatter_params.hpp"
#include "plugins/volume_singlescatter/scatter_tracer.hpp"

namespace weft {

namespace {

const Counter kShadowSamples{"shadow.samples", "density lookups for shadows, the light cache included"};
const Counter kMeshShadowRays{"mesh.shadow_rays", "shadow rays traced against the scene's meshes"};

class SingleScatter final : public Technique {
public:
    SingleScatter(const Scene& scene, const ParamSet& p) : paramSet_(p), plane_(readImagePlaneOptions(p, PlainSamples::Jittered)) {
        requireSurfaceLights(scene, "volume.singlescatter");
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        params_ = readScatterParams(paramSet_, scene, double(s.width) / s.height);
        const bool paramsWin = paramSet_.wasSet("absorb") || paramSet_.wasSet("scatter");
        std::vector<ScatterVolume> volumes = scatterVolumes(scene, params_, paramsWin);
        // An empty frame is transparent (nothing to march, nothing behind).
        if (volumes.empty() && scene.meshes.empty()) return Image::rgba(s.width, s.height);
        const MeshAccel* accel = scene.meshes.empty() ? nullptr : &scene.accel();
        ScatterTracer tracer(scene, params_, std::move(volumes), accel, accel ? rayEpsilon(scene) : 0.0f);
        if (params_.estimator == ShadowEstimator::Cached) tracer.buildCaches(ctx);
        const ImagePlane plane(plane_, s);
        const std::optional<CameraRays> still = stillCamera(scene, s);
        const std::optional<ScreenFootprint> footprint = still ? tracer.footprint(*still, s.width, s.height) : std::nullopt;
        return plane.render(ctx, "volume.singlescatter",
                            [&] { return Shader{*this, scene, tracer, s, accel != nullptr, tracer.row(), 0, still, footprint}; });
    }

private:
    // compat=vdb_render's camera stands still; the scene's moves along its keys.
    std::optional<CameraRays> stillCamera(const Scene& scene, const RenderSettings& s) const {
        if (params_.camera) return CameraRays(*params_.camera, s.width, s.height);
        return scene.stillCameraRays(s.width, s.height);
    }

    // One per row: the tracer's row state. A camera sample is one primary
    // ray; its offset along the ray and its generator are keyed by
    // (pixel, sample index). Summed in double, as before the image plane.
    struct Shader {
        const SingleScatter& self;
        const Scene& scene;
        const ScatterTracer& tracer;
        const RenderSettings& s;
        bool meshes;
        std::unique_ptr<ScatterTracer::Row, ScatterTracer::RowDeleter> row;
        std::int64_t rays = 0;
        std::optional<CameraRays> still;  // the camera's frame, where it holds all frame long
        const std::optional<ScreenFootprint>& footprint;  // the pixels whose rays can take a sample; none: all

        RgbaD operator()(const CameraSample& c) {
            Rng rng(hashCombine(s.seed, (std::uint64_t(c.py) * s.width + c.px) * 1024 + c.index));
            const float offset = self.params_.jitter ? pixelRandom(s.seed, c.px, c.py, c.index, 0) : 0.0f;
            Vec3d T(1.0);
            bool surface = false;
            ++rays;
            const Ray ray = still ? still->at(c.x, c.y) : scene.cameraAt(c.time).generate(c.x, c.y, s.width, s.height);
            const double time = scene.shutter.frameTime(0, c.time);
            const bool seen = !footprint || footprint->covers(c.x, c.y);
            const Vec3d L = tracer.radiance(ray, offset, time, *row, rng, T, surface, seen);
            return {L[0], L[1], L[2], surface ? 1.0 : 1.0 - (T[0] + T[1] + T[2]) / 3.0};
        }
        void flush(Counters& counters) const {
            const ScatterTracer::Counts& n = ScatterTracer::counts(*row);
            counters.add(kRaysCamera, rays);
            counters.add(kVolumeSamples, n.samples);
            counters.add(kShadowSamples, n.shadowSamples);
            if (meshes) counters.add(kMeshShadowRays, n.meshShadowRays);
        }
    };

    ParamSet paramSet_;
    ImagePlaneOptions plane_;
    ScatterParams params_;
};

const TechniqueRegistrar registrar{{
    "volume.singlescatter",
    "single scattering from point, directional and emissive lights, vdb_render's model and names or physical=true, faster estimators",
    ParamTable("volume.singlescatter", withImagePlaneParams(scatterParamSpecs(), PlainSamples::Jittered)),
    [](const Scene& scene, const ParamSet& p) { return std::make_unique<SingleScatter>(scene, p); },
    /*motionBlur=*/true,
    /*renders=*/Content::VolumesAndMeshes,
    /*bytesPerPixel=*/32,
    /*reference=*/{"volume.singlescatter", {"step=0.1", "shadowstep=0.25", "estimator=raymarch"}, 64},
    /*knobs=*/{{"step", {"2", "1", "0.5"}}, {"shadowstep", {"6", "3", "1"}}, {"spp", {"1", "4", "16"}},
                 {"estimator", {"cached", "raymarch"}}},
    /*scatters=*/true,
    /*velocityBlur=*/false,
    /*emission=*/true,
}};

}  // namespace

}  // namespace weft
