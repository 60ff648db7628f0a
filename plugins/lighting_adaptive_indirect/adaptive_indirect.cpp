// lighting.adaptive_indirect — adaptive sampling of the incident indirect
// illumination for a geometry-aware filter (Bauszat et al. 2011), filtered
// with the edge-avoiding A-Trous wavelet transform (Dammertz et al. 2010).
//
// A G-buffer (one ray through each pixel centre) gives normals and
// positions. The indirect budget is `spp` (the uniform rate) times the
// surface pixels; background pixels take no samples. Modes:
//   uniform          spp samples at every surface pixel, no filter
//   uniform_atrous   the same samples, A-Trous filtered
//   adaptive_atrous  the budget apportioned by geometric importance
//                    (core/screen/sample_budget.hpp: W_p over a `window`, at least
//                    max(`min_samples`, floor(`min_fraction` spp)) per
//                    pixel), A-Trous filtered
// All three trace exactly the same number of indirect samples. With
// `count_weights` (default) every filter tap is weighted by its pixel's
// sample count, so a pixel mean of many samples outweighs one of few (the
// paper's filter weighs them alike; equal counts are unaffected, so the
// uniform baseline stays the plain filter). Samples are
// generated in batches of `batch` samples through sample-to-pixel buffers
// (0: one batch per pixel count, as the paper); the image does not depend on
// the batch size or the thread count. A pixel left without samples (only
// when the budget is below the pixel count) is filled by the filter.
//
// Passes (timed): BC.gbuffer, IM.importance, SC.counts, SO.scan,
// IS.indirect (batch buffers, samples, stores), AT.atrous, C.compose.
// AOVs: indirect.RGB (the filtered incident indirect irradiance, the
// quantity the filter and the comparison work on), indirect_raw.RGB (before
// the filter), direct.RGB, albedo.RGB, N.XYZ, P.XYZ, Z, importance,
// sampleCount. The beauty is direct + kd / pi * indirect (the glossy part of
// indirect light is left out) + emission seen directly.
// Counters: samples.indirect, rays.camera, rays.indirect, rays.shadow,
// budget.active_pixels, budget.minimum (applied), budget.invalid_importance;
// with volumes volume.transmittance (segments marched), volume.steps,
// volume.lookups.
//
// Volumes absorb and out-scatter, never scatter in
// (core/lighting/volume_attenuation.hpp): a pixel's surface colour is
// multiplied by the transmittance from the eye, every indirect path segment
// and shadow ray by its own; a pixel that sees no surface has alpha
// 1 - transmittance. The budget and the filter guides are unchanged.
#include <tbb/parallel_for.h>

#include <cmath>
#include <optional>

#include "core/base/memory/large_buffer.hpp"
#include "core/base/run/progress.hpp"
#include "core/lighting/brdf.hpp"
#include "core/lighting/delta_lights.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/screen/sample_budget.hpp"
#include "plugins/filter_atrous/atrous_params.hpp"
#include "plugins/lighting_adaptive_indirect/indirect_estimator.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

const Counter kRaysIndirect{"rays.indirect", "indirect (bounce) rays traced"};
const Counter kSamplesIndirect{"samples.indirect", "indirect samples shared out over the pixels"};
const Counter kBudgetActivePixels{"budget.active_pixels", "pixels that take part in the sample budget"};
const Counter kBudgetMinimum{"budget.minimum", "samples given as the per-pixel minimum of the budget"};
const Counter kBudgetInvalidImportance{"budget.invalid_importance", "pixels whose importance was invalid or infinite"};

enum class Mode { Uniform, UniformAtrous, AdaptiveAtrous };

struct Params {
    Mode mode;
    int minSamples, window, bounces, rrDepth, directSamples;
    double minFraction;
    bool countWeights;
    double volumeStep;
    std::int64_t batch;
    AtrousSettings atrous;
};

Params readParams(const ParamSet& p) {
    Params v;
    const std::string& m = p.getString("mode");
    v.mode = m == "uniform" ? Mode::Uniform : m == "uniform_atrous" ? Mode::UniformAtrous : Mode::AdaptiveAtrous;
    v.minSamples = int(p.getInt("min_samples")), v.window = int(p.getInt("window"));
    v.bounces = int(p.getInt("bounces")), v.rrDepth = int(p.getInt("rr_depth"));
    v.directSamples = int(p.getInt("direct_samples")), v.batch = p.getInt("batch");
    v.countWeights = p.getBool("count_weights");
    v.volumeStep = p.getFloat("volume_step");
    v.minFraction = p.getFloat("min_fraction");
    v.atrous = atrousSettingsFrom(p);
    return v;
}

// The incident indirect irradiance of every pixel: the mean of its samples,
// NaN (a missing sample for the filter) where it has none.
FreshBuffer<float> sampleIndirect(const GBuffer& g, const IndirectEstimator& est, const std::vector<std::uint32_t>& counts,
                                  std::int64_t batchSize, std::uint64_t seed, const VolumeAttenuation& volumes,
                                  Counters& counters, RenderMonitor* monitor) {
    const std::vector<std::int64_t> offsets = exclusiveScan(counts);
    const SampleBatches batches(offsets, batchSize > 0 ? batchSize : std::int64_t(counts.size()));
    // Neither buffer is cleared: the passes below write every entry they
    // read, so their pages are first touched on every thread at once.
    FreshBuffer<float> sums(3 * counts.size());
    std::vector<std::uint32_t> samplePixel;
    FreshBuffer<Vec3f> results;
    Progress progress("lighting.adaptive_indirect samples", offsets.back(), monitor);
    for (std::int64_t b = 0; b < batches.count(); ++b) {
        batches.fill(b, samplePixel);
        results.resize(samplePixel.size());
        const std::int64_t b0 = batches.begin(b);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samplePixel.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
            enableFastFloatMode();
            PathRayCounts rays;
            std::optional<SegmentAttenuation> media;
            if (volumes.active()) media.emplace(volumes);
            for (std::size_t k = r.begin(); k != r.end(); ++k) {
                const std::uint32_t pixel = samplePixel[k];
                const int x = int(pixel % std::uint32_t(g.width)), y = int(pixel / std::uint32_t(g.width));
                const PixelSampler sampler(seed, x, y, batches.indexInPixel(b0 + std::int64_t(k), pixel), counts[pixel]);
                results[k] = est.irradiance(g.texels[pixel], sampler, rays, media ? &*media : nullptr);
            }
            counters.add(kRaysIndirect, rays.bounce), counters.add(kRaysShadow, rays.shadow);
            if (media) media->report(counters);
            progress.advance(std::int64_t(r.size()));
        });
        // Store: each pixel adds its samples in order, so batches change
        // nothing; the batch holding a pixel's first sample starts its sum.
        batches.forEachPixelRun(b, [&](std::uint32_t pixel, std::int64_t s0, std::int64_t s1) {
            enableFastFloatMode();
            const bool first = s0 == offsets[pixel];
            for (int c = 0; c < 3; ++c) {
                float sum = first ? 0.0f : sums[3 * pixel + c];
                for (std::int64_t s = s0; s < s1; ++s) sum += results[std::size_t(s - b0)][c];
                sums[3 * pixel + c] = sum;
            }
        });
    }
    tbb::parallel_for(std::size_t(0), counts.size(), [&](std::size_t i) {
        enableFastFloatMode();
        for (int c = 0; c < 3; ++c) sums[3 * i + c] = counts[i] ? sums[3 * i + c] / float(counts[i]) : std::nanf("");
    });
    counters.add(kSamplesIndirect, offsets.back());
    progress.finish();
    return sums;
}

class AdaptiveIndirect final : public Technique {
public:
    AdaptiveIndirect(const Scene& scene, const ParamSet& p) : p_(readParams(p)) {
        requireMeshLights(scene, "lighting.adaptive_indirect");
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        { ScopedTimer t(ctx.timings, "build_bvh"); scene.accel(); scene.emitters(); }
        GBuffer g;
        { ScopedTimer t(ctx.timings, "BC.gbuffer"); g = createGBuffer(scene, s, ctx.counters); }
        const GeometryGuides guides = guidesOf(g);
        std::vector<std::uint8_t> active(g.texels.size());
        for (std::size_t i = 0; i < active.size(); ++i) active[i] = g.texels[i].background() ? 0 : 1;
        std::vector<float> importance(g.texels.size(), 0.0f);
        const std::vector<std::uint32_t> counts = sampleCounts(guides, active, importance, s, ctx);
        const IndirectEstimator est(scene, p_.bounces, p_.rrDepth);
        FreshBuffer<float> raw;
        const VolumeAttenuation volumes(scene, p_.volumeStep);
        std::vector<Vec3f> eyeT;
        if (volumes.active()) {
            ScopedTimer t(ctx.timings, "VT.transmittance");
            eyeT = cameraTransmittance(scene, g, volumes, ctx.counters);
        }
        { ScopedTimer t(ctx.timings, "IS.indirect"); raw = sampleIndirect(g, est, counts, p_.batch, s.seed, volumes, ctx.counters, s.monitor); }
        FreshBuffer<float> filtered = copiedBuffer(raw);
        if (p_.mode != Mode::Uniform) {
            ScopedTimer t(ctx.timings, "AT.atrous");
            atrousFilter(filtered.data(), filtered.size(), g.width, g.height, guides, p_.atrous, countWeights(counts));
        }
        ScopedTimer t(ctx.timings, "C.compose");
        return compose(scene, g, est, raw, filtered, importance, counts, s.seed, volumes, eyeT, ctx.counters);
    }

private:
    // Sample counts as tap weights on every level: a pixel mean of many
    // samples outweighs one of few (equal counts change nothing).
    TapWeights countWeights(const std::vector<std::uint32_t>& counts) const {
        if (!p_.countWeights) return {};
        return TapWeights{std::vector<float>(counts.begin(), counts.end()), TapWeights::kAllLevels};
    }

    // The samples every surface pixel gets before the importance shares the rest.
    int minimumFor(int spp) const {
        return std::max(p_.minSamples, int(std::floor(p_.minFraction * double(spp))));
    }

    std::vector<std::uint32_t> sampleCounts(const GeometryGuides& guides, const std::vector<std::uint8_t>& active,
                                            std::vector<float>& importance, const RenderSettings& s, RenderContext& ctx) const {
        std::int64_t activePixels = 0;
        for (std::uint8_t a : active) activePixels += a;
        ctx.counters.add(kBudgetActivePixels, activePixels);
        if (p_.mode != Mode::AdaptiveAtrous) {
            std::vector<std::uint32_t> counts(active.size());
            for (std::size_t i = 0; i < active.size(); ++i) counts[i] = active[i] ? std::uint32_t(s.spp) : 0;
            return counts;
        }
        {
            ScopedTimer t(ctx.timings, "IM.importance");
            importance = geometryImportance(guides, {p_.window, p_.atrous.sigmaNormal, p_.atrous.sigmaPosition});
        }
        ScopedTimer t(ctx.timings, "SC.counts");
        SampleCounts c = apportionSamples(importance, active, {std::int64_t(s.spp) * activePixels, minimumFor(s.spp), s.seed});
        ctx.counters.add(kBudgetMinimum, c.minimum);
        ctx.counters.add(kBudgetInvalidImportance, c.invalidImportance + c.infiniteImportance);
        return std::move(c.counts);
    }

    Image compose(const Scene& scene, const GBuffer& g, const IndirectEstimator& est, const FreshBuffer<float>& raw,
                  const FreshBuffer<float>& filtered, const std::vector<float>& importance,
                  const std::vector<std::uint32_t>& counts, std::uint64_t seed, const VolumeAttenuation& volumes,
                  const std::vector<Vec3f>& eyeT, Counters& counters) const {
        Image img(g.width, g.height, {"R", "G", "B", "A", "indirect.R", "indirect.G", "indirect.B", "indirect_raw.R",
                                      "indirect_raw.G", "indirect_raw.B", "direct.R", "direct.G", "direct.B", "albedo.R",
                                      "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "Z", "importance",
                                      "sampleCount"});
        tbb::parallel_for(0, g.height, [&](int y) {
            enableFastFloatMode();
            PathRayCounts rays;
            std::optional<SegmentAttenuation> attenuation;
            if (volumes.active()) attenuation.emplace(volumes);
            SegmentAttenuation* media = attenuation ? &*attenuation : nullptr;
            for (int x = 0; x < g.width; ++x) {
                const std::size_t i = std::size_t(y) * g.width + x;
                const GTexel& t = g.texels[i];
                float* px = img.pixel(x, y);
                px[23] = importance[i], px[24] = float(counts[i]);
                if (t.background()) {
                    if (media) px[3] = backgroundAlpha(eyeT[i]);
                    continue;
                }
                const Vec3f wo = (Vec3f(float(scene.camera.eye.x()), float(scene.camera.eye.y()), float(scene.camera.eye.z())) - t.position).unitSafe();
                Vec3f direct(0, 0, 0);
                for (int k = 0; k < p_.directSamples; ++k) {
                    const PixelSampler sampler(seed ^ 0xd1b54a32d192ed03ull, x, y, std::uint32_t(k), std::uint32_t(p_.directSamples));
                    direct += est.direct(t.position, t.normal, wo, std::uint32_t(t.material), sampler, 0, rays, media);
                }
                direct /= float(std::max(1, p_.directSamples));
                const Material& mat = scene.materials[std::size_t(t.material)];
                if (t.front && mat.emissive()) direct += mat.emission;
                Vec3f e(filtered[3 * i], filtered[3 * i + 1], filtered[3 * i + 2]);
                if (!std::isfinite(e.x() + e.y() + e.z())) e = Vec3f(0, 0, 0);  // unsampled and unfiltered
                const Vec3f eRaw = counts[i] ? Vec3f(raw[3 * i], raw[3 * i + 1], raw[3 * i + 2]) : Vec3f(0, 0, 0);
                Vec3f rgb = direct + Brdf::of(mat).kd * e * float(1 / M_PI);
                if (media) rgb *= eyeT[i], direct *= eyeT[i];
                const float values[23] = {rgb.x(), rgb.y(), rgb.z(), 1.0f, e.x(), e.y(), e.z(), eRaw.x(), eRaw.y(), eRaw.z(),
                                          direct.x(), direct.y(), direct.z(), t.albedo.x(), t.albedo.y(), t.albedo.z(),
                                          t.normal.x(), t.normal.y(), t.normal.z(), t.position.x(), t.position.y(),
                                          t.position.z(), t.depth};
                std::copy(values, values + 23, px);
            }
            counters.add(kRaysShadow, rays.shadow);
            if (media) media->report(counters);
        });
        return img;
    }

    Params p_;
};

ParamTable table() {
    std::vector<ParamSpec> specs = {
        enumParam("mode", "adaptive_atrous", {"uniform", "uniform_atrous", "adaptive_atrous"},
                  "indirect samples: spp at every pixel (unfiltered or A-Trous filtered), or the same budget apportioned by geometric importance and filtered"),
        intParam("min_samples", 1, 0, 1 << 20,
                 "adaptive: every surface pixel gets at least max(min_samples, floor(min_fraction x spp)) samples (the paper: 1 or 2, min_fraction 0)"),
        floatParam("min_fraction", 0.75, 0, 1,
                   "adaptive: the least samples per surface pixel as a fraction of spp; the rest of the budget follows the importance"),
        intParam("window", 4, 2, 10, "adaptive: k x k window of the importance map (W_p of the normal/position weights)"),
        intParam("bounces", 2, 1, 64, "indirect bounces (1: light reflected once on its way to the pixel)"),
        intParam("rr_depth", 3, 1, 1024, "path vertices (the pixel's surface is 1) before Russian roulette may end a path"),
        intParam("direct_samples", 4, 0, 4096, "emitter samples per pixel for the direct light of the beauty image"),
        boolParam("count_weights", true,
                  "weight every A-Trous tap by its pixel's sample count (false: the plain filter, as the paper; equal counts are unaffected)"),
        intParam("batch", 0, 0, std::int64_t(1) << 32, "samples per batch (sample-to-pixel buffer size); 0: the pixel count"),
        volumeStepParam(),
    };
    for (ParamSpec& spec : atrousParamSpecs()) specs.push_back(std::move(spec));
    return ParamTable("lighting.adaptive_indirect", std::move(specs));
}

const TechniqueRegistrar registrar{{
    "lighting.adaptive_indirect",
    "indirect light sampled with a fixed budget apportioned by geometric importance, A-Trous filtered (Bauszat et al. 2011)",
    table(),
    [](const Scene& scene, const ParamSet& p) { return std::make_unique<AdaptiveIndirect>(scene, p); },
    /*motionBlur=*/false,
    /*renders=*/Content::VolumesAndMeshes,
    /*bytesPerPixel=*/224,  // G-buffer, importance, A-Trous planes (220 measured)
    /*reference=*/{"mesh.pathtrace", {}, 4096},
    /*knobs=*/{{"spp", {"1", "4", "16", "64"}}, {"mode", {"uniform", "uniform_atrous", "adaptive_atrous"}}},
}};

}  // namespace

}  // namespace weft
