// Image-plane sampling through analytic.2d: determinism, reconstruction
// across pixel boundaries, adaptive sampling, motion blur, aliasing.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "core/base/error.hpp"
#include "core/image/compare/image_spectrum.hpp"
#include "core/sampling/image_plane.hpp"
#include "plugins/host/render_job.hpp"

using namespace weft;

namespace {

RenderOutcome analytic(const std::string& scene, int size, int spp, std::vector<std::string> sets, int threads = 0) {
    RenderRequest r;
    r.input = "builtin:" + scene;
    r.resolution = Resolution{size, size};
    r.spp = spp;
    r.threads = threads;
    r.sets = std::move(sets);
    return renderToImage(r);
}

std::vector<double> errorImage(const Image& a, const Image& ref) {
    std::vector<double> e;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) e.push_back(double(a.at(x, y, 0)) - ref.at(x, y, 0));
    return e;
}

double rmse(const Image& a, const Image& ref) {
    double s = 0;
    for (double e : errorImage(a, ref)) s += e * e;
    return std::sqrt(s / (a.width() * a.height()));
}

// A vertical edge at x = 10: 1 to the left, 0 to the right.
struct EdgeShader {
    double value;
    bool edge;
    Rgba operator()(const CameraSample& c) const {
        const float v = edge ? (c.x < 10 ? 1.0f : 0.0f) : float(value);
        return {v, v, v, 1};
    }
    void flush(Counters&) const {}
};

Image renderPlane(const std::string& pattern, FilterKind filter, int spp, EdgeShader shader) {
    RenderContext ctx;
    ctx.settings.width = 20, ctx.settings.height = 6, ctx.settings.spp = spp, ctx.settings.seed = 4;
    ImagePlaneOptions o;
    o.pattern = pattern, o.filter = filter;
    return ImagePlane(o, ctx.settings).render(ctx, "test", [&] { return shader; });
}

// Keeps every camera sample where it landed, by pixel and sample index.
struct RecordingShader {
    std::vector<CameraSample>* samples;
    int width, spp;
    Rgba operator()(const CameraSample& c) const {
        (*samples)[(std::size_t(c.py) * width + c.px) * spp + c.index] = c;
        return {0, 0, 0, 1};
    }
    void flush(Counters&) const {}
};

RenderSettings planeSettings(int width, int height, int spp) {
    RenderSettings s;
    s.width = width, s.height = height, s.spp = spp, s.seed = 9;
    return s;
}

std::vector<CameraSample> plainSamples(PlainSamples plain, int spp) {
    RenderContext ctx;
    ctx.settings = planeSettings(5, 4, spp);
    std::vector<CameraSample> samples(std::size_t(5 * 4 * spp));
    ImagePlaneOptions o;
    o.plain = plain;
    ImagePlane(o, ctx.settings).render(ctx, "test", [&] { return RecordingShader{&samples, 5, spp}; });
    return samples;
}

// Cells of a pixel's n x n grid (or of n strata of one coordinate) that its samples hit.
std::size_t cellsHit(const std::vector<CameraSample>& samples, std::size_t pixel, int spp, int n, int axis) {
    std::set<int> cells;
    for (int k = 0; k < spp; ++k) {
        const CameraSample& c = samples[pixel * spp + k];
        const double u = c.x - c.px, v = c.y - c.py;
        EXPECT_TRUE(u >= 0 && u < 1 && v >= 0 && v < 1 && c.time >= 0 && c.time < 1);
        cells.insert(axis == 0 ? int(u * n) : axis == 1 ? int(v * n) : axis == 2 ? int(c.time * n) : int(u * n) + n * int(v * n));
    }
    return cells.size();
}

// 1 inside the half-plane left of a slanted line, 0 outside.
struct SlantedEdge {
    Rgba operator()(const CameraSample& c) const {
        const float v = c.x - 0.37 * c.y < 9.3 ? 1.0f : 0.0f;
        return {v, v, v, 1};
    }
    void flush(Counters&) const {}
};

Image renderEdge(PlainSamples plain, int spp) {
    RenderContext ctx;
    ctx.settings = planeSettings(20, 20, spp);
    ImagePlaneOptions o;
    o.plain = plain;
    return ImagePlane(o, ctx.settings).render(ctx, "test", [] { return SlantedEdge{}; });
}

}  // namespace

TEST(ImagePlane, JitteredPlainSamplesFillEveryCellOfTheirPixel) {
    const std::vector<CameraSample> grid = plainSamples(PlainSamples::Jittered, 16);
    const std::vector<CameraSample> latin = plainSamples(PlainSamples::Jittered, 8);
    for (std::size_t pixel = 0; pixel < 20; ++pixel) {
        EXPECT_EQ(cellsHit(grid, pixel, 16, 4, 3), 16u);  // 16 spp: one sample in each cell of a 4x4 grid
        EXPECT_EQ(cellsHit(grid, pixel, 16, 16, 2), 16u);  // and in each sixteenth of the shutter
        for (int axis = 0; axis < 3; ++axis)  // 8 spp: a Latin hypercube over x, y and time
            EXPECT_EQ(cellsHit(latin, pixel, 8, 8, axis), 8u) << axis;
    }
    for (const CameraSample& c : plainSamples(PlainSamples::Jittered, 1)) {
        EXPECT_EQ(c.x - c.px, 0.5);
        EXPECT_EQ(c.y - c.py, 0.5);
    }
}

// Wolberg 6.3.4: a stratified pixel's edge error comes only from the cells
// the edge crosses and falls as spp^-3/4, uniform samples' as spp^-1/2
// (measured: jittered/uniform 0.62 at 16 spp, 0.32 at 64; jittered 64/16 0.34).
TEST(ImagePlane, JitteredPlainSamplesHaveLessEdgeErrorThanUniformOnes) {
    const Image ref = renderEdge(PlainSamples::Jittered, 4096);
    const double jittered16 = rmse(renderEdge(PlainSamples::Jittered, 16), ref);
    const double jittered64 = rmse(renderEdge(PlainSamples::Jittered, 64), ref);
    EXPECT_LT(jittered16, 0.75 * rmse(renderEdge(PlainSamples::Uniform, 16), ref));
    EXPECT_LT(jittered64, 0.45 * rmse(renderEdge(PlainSamples::Uniform, 64), ref));
    EXPECT_LT(jittered64, 0.45 * jittered16);  // 1/sqrt(spp) would give 0.5
}

TEST(ImagePlane, SameImageOnOneAndTwoThreads) {
    const std::vector<std::vector<std::string>> cases = {
        {"pattern=interleaved:4x4,basis=lloyd"}, {"pattern=jittered", "filter=mitchell"}, {"filter=gaussian"},
        {"adaptive=supersample"}, {"adaptive=stochastic", "pattern=lp"}};
    for (const auto& sets : cases) {
        const RenderOutcome a = analytic("siemens", 40, 4, sets, 1), b = analytic("siemens", 40, 4, sets, 2);
        EXPECT_EQ(a.image.data(), b.image.data()) << sets.front();
    }
}

TEST(ImagePlane, WideFiltersReachAcrossPixelBoundaries) {
    const Image box = renderPlane("jittered", FilterKind::Box, 16, {0, true});
    const Image tent = renderPlane("jittered", FilterKind::Tent, 16, {0, true});
    EXPECT_EQ(box.at(9, 3, 0), 1.0f);
    EXPECT_EQ(box.at(10, 3, 0), 0.0f);
    EXPECT_GT(tent.at(10, 3, 0), 0.05f);  // samples of pixel 9 are within the tent's radius
    EXPECT_LT(tent.at(9, 3, 0), 0.95f);
    EXPECT_EQ(tent.at(12, 3, 0), 0.0f);  // beyond the radius nothing leaks
    EXPECT_EQ(tent.at(7, 3, 0), 1.0f);
}

TEST(ImagePlane, EveryFilterReconstructsAConstantExactly) {
    for (FilterKind k : {FilterKind::Box, FilterKind::Tent, FilterKind::Gaussian, FilterKind::Mitchell, FilterKind::BSpline,
                         FilterKind::RaisedCosine})
        for (const char* pattern : {"random", "interleaved:2x2,basis=poisson"}) {
            const Image img = renderPlane(pattern, k, 3, {0.3, false});
            for (float v : img.data()) EXPECT_TRUE(std::abs(v - 0.3f) < 1e-6f || v == 1.0f) << int(k) << " " << v;
        }
}

TEST(ImagePlane, AdaptiveSupersamplingRefinesEdgesOnly) {
    const Image ref = analytic("siemens", 64, 1, {"reference=true"}).image;
    const RenderOutcome centre = analytic("siemens", 64, 1, {});
    const RenderOutcome adaptive = analytic("siemens", 64, 1, {"adaptive=supersample", "adaptive_depth=3", "adaptive_threshold=0.01"});
    const int count = adaptive.image.channelIndex("sampleCount");
    ASSERT_GE(count, 0);
    EXPECT_EQ(adaptive.image.at(0, 0, count), 4.0f);  // the corner pixel lies inside one wedge: no split
    float most = 0;
    for (int x = 0; x < 64; ++x) most = std::max(most, adaptive.image.at(x, 20, count));
    EXPECT_GT(most, 20.0f);  // edges split to depth 3
    EXPECT_LT(rmse(adaptive.image, ref), 0.5 * rmse(centre.image, ref));
    EXPECT_LT(adaptive.counters.at("image.samples"), 16 * 64 * 64);
}

TEST(ImagePlane, AdaptiveStochasticAddsSamplesWhereContrastIsHigh) {
    const Image ref = analytic("siemens", 64, 1, {"reference=true"}).image;
    const RenderOutcome plain = analytic("siemens", 64, 4, {"pattern=interleaved:4x4"});
    const RenderOutcome adaptive =
        analytic("siemens", 64, 4, {"pattern=interleaved:4x4", "adaptive=stochastic", "adaptive_spp=32", "adaptive_threshold=0.2"});
    const int count = adaptive.image.channelIndex("sampleCount");
    int refined = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const float c = adaptive.image.at(x, y, count);
            EXPECT_TRUE(c == 4.0f || c == 36.0f);
            refined += c == 36.0f;
        }
    EXPECT_GT(refined, 100);
    EXPECT_LT(refined, 64 * 64 / 2);
    EXPECT_LT(rmse(adaptive.image, ref), 0.6 * rmse(plain.image, ref));
}

TEST(ImagePlane, MotionBlurConvergesToTheTimeAveragedDisc) {
    const Image ref = analytic("disc", 64, 1, {"reference=true"}).image;
    double previous = 1;
    for (int spp : {4, 16, 64}) {
        const double e = rmse(analytic("disc", 64, spp, {"pattern=interleaved:4x4,basis=jittered"}).image, ref);
        EXPECT_LT(e, 0.75 * previous) << spp;
        previous = e;
    }
    EXPECT_LT(previous, 0.03);
}

TEST(ImagePlane, InterleavingSplitsTheRegularGridsAliasingPeak) {
    const Image ref = analytic("grating", 64, 1, {"reference=true"}).image;
    auto peak = [&](const std::string& pattern) {
        const Image img = analytic("grating", 64, 4, pattern.empty() ? std::vector<std::string>{} : std::vector<std::string>{"pattern=" + pattern}).image;
        return coherentAliasing(errorImage(img, ref), 64, 64).ratio;
    };
    const double regular = peak("regular"), interleaved = peak("interleaved:4x4,basis=jittered"), random = peak("");
    EXPECT_GT(regular, 0.1 * 64 * 64);  // one tone (and its leakage) holds the error
    EXPECT_LT(interleaved, regular / 3);
    EXPECT_LT(random, 3 * std::log(64.0 * 64.0));  // independent per-pixel samples: noise
}

TEST(ImagePlane, InconsistentSettingsAreErrors) {
    EXPECT_THROW(analytic("siemens", 8, 1, {"adaptive=supersample", "filter=mitchell"}), Error);
    EXPECT_THROW(analytic("siemens", 8, 1, {"adaptive=supersample", "pattern=lp"}), Error);
    EXPECT_THROW(analytic("siemens", 8, 1, {"pattern=bluenoise"}), Error);
    EXPECT_THROW(analytic("siemens", 8, 1, {"pattern=interleaved:4"}), Error);
}

TEST(ImagePlane, TinyImagesAndExtremeSettingsStayFinite) {
    for (const char* scene : {"zoneplate", "grating", "checker", "siemens", "lines", "disc"})
        for (const char* size : {"1x1", "3x2", "2x7"})
            for (const std::vector<std::string>& sets :
                 std::vector<std::vector<std::string>>{{"reference=true"}, {"pattern=interleaved:3x2,basis=poisson", "filter=mitchell", "filter_radius=8"},
                                                       {"adaptive=supersample", "adaptive_depth=5", "adaptive_threshold=0"},
                                                       {"adaptive=stochastic", "adaptive_threshold=0"}}) {
                RenderRequest r;
                r.input = std::string("builtin:") + scene;
                r.resolution = parseResolution(size);
                r.spp = 3;
                r.sets = sets;
                const RenderOutcome out = renderToImage(r);
                for (float v : out.image.data()) ASSERT_TRUE(std::isfinite(v)) << scene << " " << size << " " << sets.front();
                EXPECT_EQ(out.counters.count("image.nonfinite"), 0u);
            }
}
