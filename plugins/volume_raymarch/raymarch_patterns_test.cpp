// Sample patterns in the volume techniques: image-plane supersampling in
// volume.raymarch, and interleaved per-pixel slice offsets (Keller &
// Heidrich 4.3) in volume.raymarch and volume.preint.
#include <gtest/gtest.h>

#include "core/base/error.hpp"
#include "core/image/compare/image_spectrum.hpp"
#include "tests/support/render_helpers.hpp"

using namespace weft;

namespace {

RenderOutcome renderSpp(const std::string& technique, const std::string& res, int spp, std::vector<std::string> sets,
                        int threads = 0) {
    RenderRequest r;
    r.input = "builtin:sphere";
    r.resolution = parseResolution(res);
    r.spp = spp;
    r.threads = threads;
    r.technique = technique;
    r.sets = std::move(sets);
    return renderToImage(r);
}

// RMS of the alpha error after a sigma-2 blur: the banding a viewer sees.
double blurredAlphaError(const Image& a, const Image& ref) {
    std::vector<double> e;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) e.push_back(double(a.at(x, y, 3)) - ref.at(x, y, 3));
    return blurredRms(e, a.width(), a.height(), 2.0);
}

}  // namespace

TEST(RaymarchPatterns, InterleavedSupersamplingIsDeterministicAndConverges) {
    const RenderOutcome ref = renderSpp("volume.raymarch", "24x24", 64, {"step=0.5", "pattern=jittered"});
    const RenderOutcome one = renderSpp("volume.raymarch", "24x24", 1, {"step=0.5"});
    const RenderOutcome a = renderSpp("volume.raymarch", "24x24", 4, {"step=0.5", "pattern=interleaved:2x2,basis=lp"}, 1);
    const RenderOutcome b = renderSpp("volume.raymarch", "24x24", 4, {"step=0.5", "pattern=interleaved:2x2,basis=lp"}, 2);
    EXPECT_EQ(a.image.data(), b.image.data());
    EXPECT_LT(test::rmse(a.image, ref.image), 0.8 * test::rmse(one.image, ref.image));
    EXPECT_EQ(a.counters.at("rays.camera"), 24 * 24 * 4);
}

TEST(RaymarchPatterns, WideFilterAndAdaptiveModesRunOnVolumes) {
    const RenderOutcome m = renderSpp("volume.raymarch", "16x16", 4, {"step=1", "pattern=lloyd", "filter=mitchell"});
    const RenderOutcome s = renderSpp("volume.raymarch", "16x16", 1, {"step=1", "adaptive=supersample"});
    EXPECT_GT(m.image.at(8, 8, 3), 0.5f);
    EXPECT_GE(s.image.channelIndex("sampleCount"), 0);
    EXPECT_GT(s.counters.at("rays.camera"), 17 * 17);  // corners plus refinements at the rim
}

TEST(RaymarchPatterns, InterleavedOffsetsTurnBandingIntoFineNoise) {
    const RenderOutcome ref = renderSpp("volume.raymarch", "64x64", 1, {"step=0.05", "ert=1"});
    const RenderOutcome fixed = renderSpp("volume.raymarch", "64x64", 1, {"step=6", "ert=1"});
    const RenderOutcome inter =
        renderSpp("volume.raymarch", "64x64", 1, {"step=6", "ert=1", "offset_pattern=interleaved:4x4,basis=jitter"});
    EXPECT_LT(blurredAlphaError(inter.image, ref.image), 0.7 * blurredAlphaError(fixed.image, ref.image));
    EXPECT_EQ(inter.counters.at("rays.camera"), fixed.counters.at("rays.camera"));  // same cost
    EXPECT_THROW(renderSpp("volume.raymarch", "8x8", 1, {"jitter=true", "offset_pattern=lp"}), Error);
}

TEST(PreintPatterns, InterleavedSliceOffsetsTurnSlicingArtefactsIntoFineNoise) {
    const RenderOutcome ref = renderSpp("volume.preint", "64x64", 1, {"spacing=0.1"});
    const RenderOutcome fixed = renderSpp("volume.preint", "64x64", 1, {"spacing=8"});
    const RenderOutcome inter = renderSpp("volume.preint", "64x64", 1, {"spacing=8", "offset_pattern=interleaved:4x4,basis=jitter"});
    EXPECT_LT(blurredAlphaError(inter.image, ref.image), 0.5 * blurredAlphaError(fixed.image, ref.image));
    const double ratio = double(inter.counters.at("volume.samples")) / double(fixed.counters.at("volume.samples"));
    EXPECT_NEAR(ratio, 1.0, 0.05);  // the same number of slices per ray
    const RenderOutcome a = renderSpp("volume.preint", "32x32", 1, {"spacing=4", "offset_pattern=interleaved:4x4"}, 1);
    const RenderOutcome b = renderSpp("volume.preint", "32x32", 1, {"spacing=4", "offset_pattern=interleaved:4x4"}, 2);
    EXPECT_EQ(a.image.data(), b.image.data());
}
