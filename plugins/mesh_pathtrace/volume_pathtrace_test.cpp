// mesh.pathtrace with volumes: thread-count independence on a combined
// scene, volumes and meshes both contribute, volume-only renders composite
// (alpha = 1 - transmittance), a volume-only scene without lights is an
// error, extreme coefficients give finite images, both shadow estimators
// agree in the mean.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/error.hpp"
#include "core/scene/scene.hpp"
#include "tests/support/mesh_fixtures.hpp"
#include "tests/support/render_helpers.hpp"

using namespace weft;

namespace {

const std::string kSmoke = std::string(WEFT_SOURCE_DIR) + "/scenes/combined/smoke_over_ground.json";

Scene smokeOverGround() { return loadScene(kSmoke, 4.0 / 3.0); }

Image renderSmoke(const Scene& scene, std::map<std::string, std::string> params, int spp = 16, std::uint64_t seed = 1) {
    return test::renderScene(scene, "mesh.pathtrace", params, 32, 24, spp, seed);
}

bool allFinite(const Image& img) {
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
            for (int c = 0; c < 4; ++c)
                if (!std::isfinite(img.at(x, y, c))) return false;
    return true;
}

}  // namespace

TEST(VolumePathTrace, SameImageAtOneAndTwoThreads) {
    const RenderOutcome a = test::render(kSmoke, "24x18", {"max_depth=4"}, "mesh.pathtrace", 1);
    const RenderOutcome b = test::render(kSmoke, "24x18", {"max_depth=4"}, "mesh.pathtrace", 2);
    EXPECT_EQ(a.image.data(), b.image.data());
    EXPECT_GT(test::channelMean(a.image, 0), 0.01);
}

TEST(VolumePathTrace, CombinedSceneDiffersFromEachPart) {
    const Scene both = smokeOverGround();
    Scene meshOnly = both, volumeOnly = both;
    meshOnly.volumes.clear();
    volumeOnly.meshes.clear(), volumeOnly.materials.clear();
    const Image combined = renderSmoke(both, {}), meshes = renderSmoke(meshOnly, {}), volumes = renderSmoke(volumeOnly, {});
    // The smoke shadows the ground and adds its own light; the ground lights
    // the smoke from below: each part differs clearly from the whole.
    EXPECT_GT(test::rmse(combined, meshes), 0.02);
    EXPECT_GT(test::rmse(combined, volumes), 0.02);
    EXPECT_EQ(combined.at(0, 23, 3), 1.0f);  // the ground covers the bottom
}

TEST(VolumePathTrace, VolumeOnlyAlphaIsOneMinusTransmittance) {
    Scene scene = smokeOverGround();
    scene.meshes.clear(), scene.materials.clear();
    const Image img = renderSmoke(scene, {{"max_depth", "1"}}, 32);
    double minAlpha = 1, maxAlpha = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) {
            minAlpha = std::min(minAlpha, double(img.at(x, y, 3))), maxAlpha = std::max(maxAlpha, double(img.at(x, y, 3)));
            if (img.at(x, y, 3) == 0.0f) {
                ASSERT_EQ(img.at(x, y, 0), 0.0f);  // nothing seen: nothing added
            }
        }
    EXPECT_EQ(minAlpha, 0.0);  // rays that miss the smoke
    EXPECT_GT(maxAlpha, 0.5);  // the dense core
    EXPECT_LT(maxAlpha, 1.0 + 1e-6);
}

TEST(VolumePathTrace, VolumeOnlySceneNeedsALight) {
    Scene scene = smokeOverGround();
    scene.meshes.clear(), scene.materials.clear(), scene.lights.clear();
    try {
        renderSmoke(scene, {});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no light"), std::string::npos) << e.what();
    }
}

TEST(VolumePathTrace, ExtremeCoefficientsGiveFiniteImages) {
    for (double k : {1e-30, 1e12}) {
        Scene scene = smokeOverGround();
        scene.volumes[0].medium.absorb = Vec3d(k), scene.volumes[0].medium.scatter = Vec3d(k);
        const Image img = test::renderScene(scene, "mesh.pathtrace", {{"max_depth", "3"}}, 8, 6, 2, 3);
        EXPECT_TRUE(allFinite(img)) << k;
    }
}

TEST(VolumePathTrace, ShadowEstimatorsAgreeInTheMean) {
    Scene scene = smokeOverGround();
    const Image ratio = renderSmoke(scene, {{"max_depth", "1"}, {"shadow_tracking", "ratio"}}, 64, 5);
    const Image delta = renderSmoke(scene, {{"max_depth", "1"}, {"shadow_tracking", "delta"}}, 64, 6);
    for (int c = 0; c < 3; ++c) {
        const double a = test::channelMean(ratio, c), b = test::channelMean(delta, c);
        EXPECT_NEAR(a, b, 0.02 * a) << "channel " << c;
    }
}

TEST(VolumePathTrace, SingleScatteringIsDarkerThanMultiple) {
    const Scene scene = smokeOverGround();
    Scene volumeOnly = scene;
    volumeOnly.meshes.clear(), volumeOnly.materials.clear();
    const double single = test::channelMean(renderSmoke(volumeOnly, {{"max_depth", "1"}}, 32), 1);
    const double multiple = test::channelMean(renderSmoke(volumeOnly, {{"max_depth", "16"}}, 32), 1);
    EXPECT_GT(multiple, single * 1.05);  // albedo 0.95: higher orders add light
}
