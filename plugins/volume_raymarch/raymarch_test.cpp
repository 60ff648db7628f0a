// volume.raymarch against closed forms, its own options, and at extremes.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/error.hpp"
#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;
using weft::test::render;

namespace {

bool allFinite(const Image& img) {
    for (float v : img.data())
        if (!std::isfinite(v)) return false;
    return true;
}

}  // namespace

TEST(Raymarch, CentreRayOfHomogeneousSphereMatchesBeerLambert) {
    // builtin:sphere: 64^3 voxels, density 1 inside radius 0.4 (25.6 voxels),
    // white, extinction 0.05 per voxel. The centre pixel of an odd-sized
    // image looks through the centre: a chord of 51.2 voxels.
    const RenderOutcome out = render("builtin:sphere", "33x33", {"step=0.02", "ert=1"});
    const double expected = 1.0 - std::exp(-0.05 * 51.2);
    EXPECT_NEAR(out.image.at(16, 16, 3), expected, 2e-3);
    EXPECT_NEAR(out.image.at(16, 16, 0), expected, 2e-3);  // white emission: colour = opacity
    EXPECT_EQ(out.image.at(0, 0, 3), 0.0f);
}

TEST(Raymarch, CountsCameraRaysAndSamples) {
    const RenderOutcome a = render("builtin:sphere", "16x16", {"step=1"});
    const RenderOutcome b = render("builtin:sphere", "16x16", {"step=0.5"});
    EXPECT_EQ(a.counters.at("rays.camera"), 256);
    const double ratio = double(b.counters.at("volume.samples")) / double(a.counters.at("volume.samples"));
    EXPECT_NEAR(ratio, 2.0, 0.05);  // half the step, twice the samples
}

TEST(Raymarch, SkipEmptyGivesTheSameImageWithFewerSamples) {
    const RenderOutcome full = render("builtin:cloud", "48x48", {"step=0.5"});
    const RenderOutcome skip = render("builtin:cloud", "48x48", {"step=0.5", "skip_empty=true"});
    EXPECT_EQ(full.image.data(), skip.image.data());
    EXPECT_LT(skip.counters.at("volume.samples"), full.counters.at("volume.samples"));
}

TEST(Raymarch, EarlyTerminationStopsAtTheRequestedOpacity) {
    const RenderOutcome full = render("builtin:sphere", "17x17", {"step=0.25", "ert=1"});
    const RenderOutcome early = render("builtin:sphere", "17x17", {"step=0.25", "ert=0.5"});
    EXPECT_LT(early.counters.at("volume.samples"), full.counters.at("volume.samples"));
    EXPECT_GE(early.image.at(8, 8, 3), 0.5f);
    EXPECT_LT(early.image.at(8, 8, 3), full.image.at(8, 8, 3));
}

TEST(Raymarch, JitterIsDeterministicAndUnbiased) {
    const RenderOutcome a = render("builtin:sphere", "24x24", {"step=2", "jitter=true"});
    const RenderOutcome b = render("builtin:sphere", "24x24", {"step=2", "jitter=true"});
    EXPECT_EQ(a.image.data(), b.image.data());
    const RenderOutcome ref = render("builtin:sphere", "24x24", {"step=0.05"});
    const RenderOutcome fixed = render("builtin:sphere", "24x24", {"step=2"});
    // Jitter trades the fixed phase's structured error for noise of similar size.
    EXPECT_LT(test::rmse(a.image, ref.image), 3.0 * test::rmse(fixed.image, ref.image) + 1e-3);
}

TEST(Raymarch, ExtremeStepsAndExtinctionsStayFinite) {
    test::TempDir dir;
    test::writeText(dir / "dense.json", R"({"volumes": [{"procedural": "cloud", "resolution": 16,
        "transfer_function": {"points": [{"s": 0, "extinction": 0}, {"s": 1, "extinction": 1e30}]}}]})");
    test::writeText(dir / "thin.json", R"({"volumes": [{"procedural": "cloud", "resolution": 16,
        "transfer_function": {"points": [{"s": 0, "extinction": 0}, {"s": 1, "extinction": 1e-30}]}}]})");
    for (const std::string step : {"0.0001", "64"}) {
        for (const char* scene : {"dense.json", "thin.json"}) {
            const RenderOutcome out = render((dir / scene).string(), "6x6", {"step=" + step, "ert=1"});
            EXPECT_TRUE(allFinite(out.image)) << scene << " step " << step;
            for (float v : out.image.data()) EXPECT_LE(v, 1.0f + 1e-6f);
            EXPECT_EQ(out.counters.count("image.nonfinite"), 0u);
        }
    }
}

TEST(Raymarch, RejectsSceneItCannotRender) {
    test::TempDir dir;
    test::writeText(dir / "fog.json", R"({"volumes": [{"procedural": "sphere", "resolution": 8,
        "transfer_function": {"points": [{"s": 0, "extinction": 0.1}]}}]})");
    EXPECT_THROW(render((dir / "fog.json").string(), "4x4", {"skip_empty=true"}), Error);
}
