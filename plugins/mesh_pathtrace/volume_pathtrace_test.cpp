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

TEST(VolumePathTrace, CameraRayAlphaIsOneMinusTheClosedFormTransmittance) {
    // A homogeneous cube of 16^3 voxels stretched 3x along z, seen along z
    // through its centre: the trilinear ramps at both faces add half a voxel
    // each, so the optical depth is 16 voxels of 3 h at sigma = k / voxelLength
    // with voxelLength = h 3^(1/3): tau = 16 k 3^(2/3).
    initVdb();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(1.0 / 16));
    grid->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(15)), 1.0f, true);
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.preTranslate(Vec3d(-0.5 + 0.5 / 16, -0.5 + 0.5 / 16, -0.5 + 0.5 / 16));
    m.postScale(Vec3d(1, 1, 3));
    Volume v;
    v.grid = placeGrid(grid, m);
    const double k = 0.02;
    v.medium.absorb = Vec3d(k / 2), v.medium.scatter = Vec3d(k / 2);
    computeStatistics(v);
    Scene scene;
    scene.source = "stretched cube";
    scene.volumes.push_back(v);
    scene.lights.push_back(Light{});
    scene.camera.eye = Vec3d(0, 0, 6), scene.camera.target = Vec3d(0, 0, 0);
    const int n = 20000;
    const Image img = test::renderScene(scene, "mesh.pathtrace", {{"max_depth", "1"}, {"jitter", "false"}}, 1, 1, n, 4);
    const double T = std::exp(-16 * k * std::pow(3.0, 2.0 / 3.0));
    EXPECT_NEAR(img.at(0, 0, 3), 1 - T, 4 * std::sqrt(T * (1 - T) / n)) << "T " << T;
}
