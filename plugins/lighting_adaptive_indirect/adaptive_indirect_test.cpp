// lighting.adaptive_indirect: its indirect light agrees with mesh.pathtrace
// (with and without the diffuse albedo), all three modes trace the same
// number of samples and the sampleCount AOV adds up to it, the image is the
// same for any thread count and batch size, and the adaptive mode puts more
// samples on edges and lowers the filtered error on the Cornell box.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/image/compare/image_compare.hpp"
#include "tests/support/mesh_fixtures.hpp"
#include "tests/support/render_helpers.hpp"

using namespace weft;

namespace {

const std::string kCornell = std::string(WEFT_SOURCE_DIR) + "/scenes/cornell.json";

RenderOutcome renderCornell(const std::string& res, int spp, std::vector<std::string> sets, std::uint64_t seed = 1,
                            int threads = 0, const std::string& technique = "lighting.adaptive_indirect") {
    RenderRequest r;
    r.input = kCornell, r.resolution = parseResolution(res), r.technique = technique, r.sets = std::move(sets);
    r.spp = spp, r.seed = seed, r.threads = threads;
    return renderToImage(r);
}

double meanOf(const Image& img, const std::string& channel) {
    const int c = img.channelIndex(channel);
    EXPECT_GE(c, 0) << channel;
    return test::channelMean(img, c);
}

// Mean squared error of the indirect.RGB layer against a reference's.
double indirectMse(const Image& img, const Image& ref) {
    double sum = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
            for (const char* ch : {"indirect.R", "indirect.G", "indirect.B"}) {
                const double d = img.at(x, y, img.channelIndex(ch)) - ref.at(x, y, ref.channelIndex(ch));
                sum += d * d;
            }
    return sum / (3.0 * img.width() * img.height());
}

}  // namespace

TEST(AdaptiveIndirect, ReflectedIndirectLightMatchesThePathTracer) {
    // mesh.pathtrace at pixel centres: depth 3 minus depth 1 is the light
    // that bounced once or twice, which is kd / pi * E here (no glossy material).
    const Image full = renderCornell("24x24", 512, {"max_depth=3", "jitter=false"}, 3, 0, "mesh.pathtrace").image;
    const Image direct = renderCornell("24x24", 512, {"max_depth=1", "jitter=false"}, 3, 0, "mesh.pathtrace").image;
    const Image ours = renderCornell("24x24", 256, {"mode=uniform", "bounces=2", "direct_samples=0"}, 4).image;
    for (int c = 0; c < 3; ++c) {
        const char* ch[] = {"R", "G", "B"};
        const double expected = test::channelMean(full, c) - test::channelMean(direct, c);
        const double indirect = meanOf(ours, ch[c]) - meanOf(ours, std::string("direct.") + ch[c]);  // direct: emission only here
        EXPECT_NEAR(indirect, expected, 0.03 * expected) << ch[c];
    }
}

TEST(AdaptiveIndirect, ModesTraceTheSameBudgetAndTheCountAovAddsUp) {
    std::int64_t samples[3];
    int k = 0;
    for (const char* mode : {"uniform", "uniform_atrous", "adaptive_atrous"}) {
        const RenderOutcome out = renderCornell("40x30", 3, {std::string("mode=") + mode, "min_samples=1", "min_fraction=0"});
        samples[k] = out.counters.at("samples.indirect");
        EXPECT_EQ(samples[k], 3 * out.counters.at("budget.active_pixels")) << mode;
        EXPECT_NEAR(meanOf(out.image, "sampleCount") * 40 * 30, double(samples[k]), 1e-6) << mode;
        ++k;
    }
    EXPECT_EQ(samples[0], samples[2]);
}

TEST(AdaptiveIndirect, MinimumIsTheLargerOfMinSamplesAndTheRateFraction) {
    struct Case { const char* minSamples; const char* minFraction; int spp; std::int64_t minimum; };
    for (const Case& c : {Case{"min_samples=1", "min_fraction=0.5", 8, 4}, Case{"min_samples=6", "min_fraction=0.5", 8, 6},
                          Case{"min_samples=1", "min_fraction=0.75", 4, 3}, Case{"min_samples=2", "min_fraction=0", 4, 2},
                          Case{"min_samples=1", "min_fraction=1", 4, 4}}) {
        const RenderOutcome out = renderCornell("40x30", c.spp, {"mode=adaptive_atrous", c.minSamples, c.minFraction});
        EXPECT_EQ(out.counters.at("budget.minimum"), c.minimum) << c.minSamples << " " << c.minFraction;
        const int cc = out.image.channelIndex("sampleCount"), cn = out.image.channelIndex("N.Z");
        float least = 1e9f;
        for (int y = 0; y < 30; ++y)
            for (int x = 0; x < 40; ++x)
                if (out.image.at(x, y, cn) != 0) least = std::min(least, out.image.at(x, y, cc));
        EXPECT_GE(least, float(c.minimum)) << c.minSamples << " " << c.minFraction;
    }
}

TEST(AdaptiveIndirect, SameImageForAnyThreadCountAndBatchSize) {
    const Image a = renderCornell("33x21", 4, {"batch=0"}, 7, 1).image;
    const Image b = renderCornell("33x21", 4, {"batch=97"}, 7, 2).image;
    const Image c = renderCornell("33x21", 4, {"batch=100000"}, 7, 2).image;
    for (const Image* other : {&b, &c})
        for (std::size_t i = 0; i < a.data().size(); ++i)
            ASSERT_EQ(a.data()[i], other->data()[i]) << a.channelNames()[i % a.channelCount()] << " pixel " << i / a.channelCount();
}

TEST(AdaptiveIndirect, AdaptiveSamplesEdgesMoreAndLowersTheFilteredError) {
    const Image ref = renderCornell("48x48", 512, {"mode=uniform"}, 11).image;
    const Image uni = renderCornell("48x48", 4, {"mode=uniform_atrous"}, 12).image;
    const Image ada = renderCornell("48x48", 4, {"mode=adaptive_atrous", "min_samples=1", "min_fraction=0"}, 12).image;
    // The count follows the importance: the most important fifth of the
    // pixels gets more samples on average than the least important half.
    const int ci = ada.channelIndex("importance"), cc = ada.channelIndex("sampleCount");
    std::vector<std::pair<float, float>> byImportance;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 48; ++x) byImportance.emplace_back(ada.at(x, y, ci), ada.at(x, y, cc));
    std::sort(byImportance.begin(), byImportance.end());
    const std::size_t n = byImportance.size();
    double lo = 0, hi = 0;
    for (std::size_t i = 0; i < n / 2; ++i) lo += byImportance[i].second / double(n / 2);
    for (std::size_t i = n - n / 5; i < n; ++i) hi += byImportance[i].second / double(n / 5);
    EXPECT_GT(hi, 1.2 * lo);
    EXPECT_LT(indirectMse(ada, ref), indirectMse(uni, ref));
}

TEST(AdaptiveIndirect, CountWeightsChangeNothingAtEqualCounts) {
    const Image on = renderCornell("30x20", 3, {"mode=uniform_atrous", "count_weights=true"}, 5).image;
    const Image off = renderCornell("30x20", 3, {"mode=uniform_atrous", "count_weights=false"}, 5).image;
    for (std::size_t i = 0; i < on.data().size(); ++i) ASSERT_NEAR(on.data()[i], off.data()[i], 1e-5f * (1 + std::abs(off.data()[i]))) << i;
}

TEST(AdaptiveIndirect, NoNanWithFewerSamplesThanPixelsOrNoFilterLevels) {
    for (const std::vector<std::string>& sets : {std::vector<std::string>{"min_samples=0", "min_fraction=0", "window=10"},
                                                 std::vector<std::string>{"levels=0", "min_samples=0", "min_fraction=0"},
                                                 std::vector<std::string>{"sigma_normal=0", "sigma_position=0", "sigma_color=0.001"}}) {
        const Image img = renderCornell("20x20", 1, sets).image;
        for (float v : img.data()) ASSERT_TRUE(std::isfinite(v));
    }
}
