// volume.raymarch — emission-absorption ray marching at a fixed step.
//
// Each camera ray is clipped to the volume's index box and sampled every
// `step` voxels with trilinear interpolation (OpenVDB BoxSampler); each
// sample's transfer-function colour and extinction make a segment of opacity
// 1 - exp(-extinction * step), composited front to back. With a very small
// step this is the reference other volume techniques are measured against.
//
// Parameters (see `weft help volume.raymarch`):
//   step        distance between samples, in voxels (the speed/accuracy knob)
//   jitter      random offset of the first sample per ray (banding -> noise)
//   ert         early ray termination once opacity reaches this (1 = off)
//   skip_empty  skip regions without active voxels (OpenVDB HDDA); the image
//               is unchanged, only fewer samples are taken
//   offset_pattern  per-pixel offsets of the first sample from a pattern set's
//               third coordinate: interleaved:4x4 gives the 16 pixels of each
//               tile 16 different strata of the step (Keller & Heidrich 4.3)
//   pattern, filter, adaptive...  image-plane sampling and reconstruction
//               (core/sampling/image_plane.hpp)
//
// Counters: rays.camera, volume.samples (trilinear lookups of the grid).
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/RayIntersector.h>

#include <optional>

#include "core/sampling/pixel_loop.hpp"
#include "core/base/rng.hpp"
#include "core/sampling/image_plane.hpp"
#include "core/volume/volume_ray.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

using Sampler = openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>;
using Intersector = openvdb::tools::VolumeRayIntersector<openvdb::FloatGrid, 0>;

struct RaymarchParams {
    double step;
    bool jitter;
    float ertOpacity;
    bool skipEmpty;
    std::string offsetPattern;
};

std::vector<ParamSpec> raymarchParams() {
    std::vector<ParamSpec> specs = {
        floatParam("step", 0.5, 1e-4, 64, "distance between samples along a ray, in voxels"),
        boolParam("jitter", false, "random per-ray offset of the first sample (trades banding for noise)"),
        floatParam("ert", 0.99, 0, 1, "early ray termination once opacity reaches this (1 = never)"),
        boolParam("skip_empty", false, "skip regions without active voxels (OpenVDB HDDA); same image, fewer samples"),
        stringParam("offset_pattern", "", "offset of the first sample per pixel from a pattern set's third coordinate, "
                                          "e.g. interleaved:4x4,basis=jittered (Keller & Heidrich 4.3); empty: jitter or centre",
                    [](const std::string& v) { if (!v.empty()) validatePatternSpec(v); }),
    };
    for (ParamSpec& spec : imagePlaneParamSpecs()) specs.push_back(std::move(spec));
    return specs;
}

class Raymarch final : public Technique {
public:
    Raymarch(const Scene& scene, const ParamSet& p)
        : params_{p.getFloat("step"), p.getBool("jitter"), float(p.getFloat("ert")), p.getBool("skip_empty"),
                  p.getString("offset_pattern")},
          plane_(readImagePlaneOptions(p)) {
        if (params_.jitter && !params_.offsetPattern.empty())
            throw Error("volume.raymarch: jitter=true and offset_pattern both set the first sample's offset; choose one");
        if (scene.volumes.size() != 1)
            throw Error("volume.raymarch renders exactly one volume; the scene has " + std::to_string(scene.volumes.size()));
        const Volume& vol = scene.volumes.front();
        if (params_.skipEmpty && vol.tf.lookup(vol.grid->background()).extinction > 0)
            throw Error("volume.raymarch: skip_empty=true needs a transfer function that is transparent at the grid's background value");
        // Trilinear support reaches the 26 neighbours of an active voxel; three
        // face-neighbour dilations cover them all (Manhattan distance <= 3).
        if (params_.skipEmpty) intersector_.emplace(*vol.grid, 3);
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        std::optional<PatternSet> offsets;
        if (!params_.offsetPattern.empty()) offsets = makePatternSet(params_.offsetPattern, s.spp, hashCombine(s.seed, 0x0ff5));
        const ImagePlane plane(plane_, s);
        // One per row: its own grid accessor and HDDA, and its counts.
        struct Shader {
            const Raymarch& self;
            const Scene& scene;
            const RenderSettings& s;
            const std::optional<PatternSet>& offsets;
            openvdb::FloatGrid::ConstAccessor accessor;
            Sampler sampler;  // keeps a pointer to accessor: Shader is built in place, never copied
            std::optional<Intersector> hdda;
            std::int64_t samples = 0, rays = 0;

            Shader(const Raymarch& r, const Scene& sc, const RenderSettings& st, const std::optional<PatternSet>& o)
                : self(r), scene(sc), s(st), offsets(o), accessor(sc.volumes.front().grid->getConstAccessor()),
                  sampler(accessor, sc.volumes.front().grid->transform()) {
                if (r.intersector_) hdda.emplace(*r.intersector_);
            }
            Rgba operator()(const CameraSample& c) {
                const Ray ray = scene.cameraAt(c.time).generate(c.x, c.y, s.width, s.height);
                float offset = self.params_.jitter ? pixelRandom(s.seed, c.px, c.py, c.index, 0) : 0.5f;
                if (offsets) offset = offsets->sample(c.px, c.py, int(c.index % std::uint32_t(s.spp))).t;
                const RayAccumulator acc =
                    self.march(scene.volumes.front(), ray, offset, sampler, hdda ? &*hdda : nullptr, samples);
                ++rays;
                return {acc.r, acc.g, acc.b, acc.opacity()};
            }
            void flush(Counters& counters) const {
                counters.add("rays.camera", rays);
                counters.add("volume.samples", samples);
            }
        };
        return plane.render(ctx, "volume.raymarch", [&] { return Shader(*this, scene, s, offsets); });
    }

private:
    // Samples t_k = t0 + (k + offset) * step for every k inside [lo, hi).
    void marchInterval(const Volume& vol, const IndexRay& ray, double lo, double hi, float offset,
                       Sampler& sampler, RayAccumulator& acc, std::int64_t& samples) const {
        const double h = params_.step;
        const double kFirst = std::max(0.0, std::ceil((lo - ray.t0) / h - offset));
        for (double k = kFirst;; k += 1.0) {
            const double t = ray.t0 + (k + offset) * h;
            if (t >= hi || t >= ray.t1) break;
            const float value = sampler.isSample(ray.at(t));
            ++samples;
            const TfSample c = vol.tf.lookup(value);
            acc.add(c, segmentOpacity(c.extinction, float(h)));
            if (acc.opacity() >= params_.ertOpacity) return;
        }
    }

    RayAccumulator march(const Volume& vol, const Ray& worldRay, float offset, Sampler& sampler,
                         Intersector* hdda, std::int64_t& samples) const {
        RayAccumulator acc;
        const auto ray = toIndexRay(worldRay, vol);
        if (!ray) return acc;
        if (!hdda) {
            marchInterval(vol, *ray, ray->t0, ray->t1, offset, sampler, acc, samples);
            return acc;
        }
        const openvdb::math::Ray<double> iray(ray->origin, ray->dir, ray->t0, ray->t1);
        if (!hdda->setIndexRay(iray)) return acc;
        double a = 0, b = 0;
        while (hdda->march(a, b) && acc.opacity() < params_.ertOpacity)
            marchInterval(vol, *ray, a, b, offset, sampler, acc, samples);
        return acc;
    }

    RaymarchParams params_;
    ImagePlaneOptions plane_;
    std::optional<Intersector> intersector_;
};

const TechniqueRegistrar registrar{{
    "volume.raymarch",
    "emission-absorption ray marching at a fixed step (the reference volume renderer)",
    ParamTable("volume.raymarch", raymarchParams()),
    [](const Scene& scene, const ParamSet& p) { return std::make_unique<Raymarch>(scene, p); },
    /*motionBlur=*/true,
}};

}  // namespace

}  // namespace weft
