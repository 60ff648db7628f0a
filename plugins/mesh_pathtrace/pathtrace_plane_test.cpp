// mesh.pathtrace through the image plane: interleaved patterns and wide
// filters are deterministic at any thread count and converge to the default
// image; jitter=false keeps pixel centres; bad sampling settings are errors.
#include <gtest/gtest.h>

#include "tests/support/image_plane_checks.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;

namespace {

const std::string kCornell = std::string(WEFT_SOURCE_DIR) + "/scenes/cornell.json";
const std::string kSmoke = std::string(WEFT_SOURCE_DIR) + "/scenes/combined/smoke_in_cornell.json";
const char* kTech = "mesh.pathtrace";

}  // namespace

TEST(PathTracePlane, InterleavedPatternConvergesToTheDefault) {
    test::expectImagePlaneVariant(kCornell, kTech, "32x32", 16, {}, "pattern=interleaved:4x4,basis=lp");
}

TEST(PathTracePlane, MitchellFilterConvergesToTheDefault) {
    test::expectImagePlaneVariant(kCornell, kTech, "32x32", 16, {}, "filter=mitchell");
}

TEST(PathTracePlane, VolumetricPathsThroughAPatternAreDeterministic) {
    // Medium rows (free flights, shadow rays) live in the plane's per-row shader.
    test::expectImagePlaneVariant(kSmoke, kTech, "24x24", 8, {"max_depth=3"}, "pattern=interleaved:4x4,basis=lp");
}

TEST(PathTracePlane, AdaptiveStochasticAddsSamplesWhereTheyDiffer) {
    RenderRequest r;
    r.input = kCornell, r.technique = kTech, r.resolution = Resolution{16, 16}, r.spp = 4, r.seed = 3;
    r.sets = {"adaptive=stochastic", "adaptive_spp=8"};
    const RenderOutcome out = renderToImage(r);
    const std::int64_t samples = out.counters.at("image.samples");
    EXPECT_GT(samples, 16 * 16 * 4);
    EXPECT_LT(samples, 16 * 16 * 12);
    EXPECT_EQ(out.counters.at("rays.camera"), samples);
}

TEST(PathTracePlane, WithoutJitterEverySampleTakesThePixelCentre) {
    // Direct light from a directional light is free of noise, so with every
    // sample through the pixel centre 4 spp give the 1 spp image; jittered
    // samples see the ground's edge differently.
    test::TempDir dir;
    const std::string scene = (dir / "ground.json").string();
    test::writeText(scene, R"({"camera": {"eye": [1.6, 1.3, 2.6], "target": [0, 0.45, 0], "up": [0, 1, 0], "fov": 40},
        "meshes": [{"file": ")" + std::string(WEFT_SOURCE_DIR) + R"(/data/shapes/ground.obj"}],
        "lights": [{"type": "directional", "direction": [-0.45, -1, -0.3], "intensity": 3}]})");
    const std::vector<std::string> direct = {"max_depth=1"};
    std::vector<std::string> centres = direct;
    centres.push_back("jitter=false");
    const Image one = test::renderPlane(scene, kTech, "16x12", 1, 5, centres);
    const Image four = test::renderPlane(scene, kTech, "16x12", 4, 5, centres);
    const Image jittered = test::renderPlane(scene, kTech, "16x12", 4, 5, direct);
    float centreError = 0, jitterChange = 0;
    for (std::size_t i = 0; i < one.data().size(); ++i) {
        centreError = std::max(centreError, std::abs(four.data()[i] - one.data()[i]));
        jitterChange = std::max(jitterChange, std::abs(jittered.data()[i] - one.data()[i]));
    }
    EXPECT_LT(centreError, 1e-6f);
    EXPECT_GT(jitterChange, 0.01f);
}

TEST(PathTracePlane, BadSamplingSettingsAreOneLineErrors) {
    test::expectBadPatternNamed(kCornell, kTech);
    EXPECT_THROW(test::renderPlane(kCornell, kTech, "8x8", 4, 0, {"jitter=false", "pattern=interleaved:2x2"}), Error);
}
