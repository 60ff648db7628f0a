// Velocity motion blur in the scattering techniques (volume.singlescatter,
// mesh.pathtrace): the translating blob of the raymarch tests
// (tests/support/moving_blob.hpp), in a medium under a directional light,
// against the static blob seen by a camera moving the other way. Under a
// directional light a translation moves the shading with the volume, so
// the two pictures are the same up to the estimators' noise (measured as
// the distance between two seeds of the camera render) and the march's
// discretisation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include "core/scene/scene.hpp"
#include "tests/support/moving_blob.hpp"
#include "tests/support/render_helpers.hpp"

using namespace weft;

namespace {

constexpr double kVelocity = 18;  // world units per second: the blob sweeps 0.75 over a one-frame shutter

Image renderWith(const std::string& scene, const std::string& technique, const std::vector<std::string>& sets, int spp,
                 std::uint64_t seed = 1, int threads = 0) {
    RenderRequest r;  // at frame 0: between the moving camera's keys
    r.input = scene, r.resolution = Resolution{40, 24}, r.sets = sets, r.technique = technique, r.spp = spp, r.seed = seed, r.threads = threads;
    r.frame = 0;
    return renderToImage(r).image;
}

double totalOf(const Image& img) {
    double sum = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) sum += img.at(x, y, 0);
    return sum;
}

// Running mean and variance (of a few renders' totals).
struct Stats {
    std::vector<double> values;
    void add(double v) { values.push_back(v); }
    double mean() const { return std::accumulate(values.begin(), values.end(), 0.0) / double(values.size()); }
    double varianceOfMean() const {
        double ss = 0;
        for (double v : values) ss += (v - mean()) * (v - mean());
        return ss / double(values.size() - 1) / double(values.size());
    }
};

struct BlurCase {
    std::string technique;
    std::vector<std::string> sets;
    int spp;
};

// RMSE(velocity blur, camera blur) and the noise floor RMSE(camera seed 1, seed 2).
void expectVelocityBlurEqualsCameraBlur(const BlurCase& c) {
    test::TempDir dir;
    test::writeBlob(dir / "blob.vdb", {float(kVelocity), 0, 0});
    const test::BlobLook look = test::scatteringLook();
    const Image moving = renderWith(test::movingBlobScene(dir, look), c.technique, c.sets, c.spp);
    const std::string cameraScene = test::movingCameraBlobScene(dir, look, kVelocity);
    const Image camera = renderWith(cameraScene, c.technique, c.sets, c.spp);
    const Image camera2 = renderWith(cameraScene, c.technique, c.sets, c.spp, 2);
    const Image still = renderWith(test::movingBlobScene(dir, look, "[0, 0]"), c.technique, c.sets, c.spp);
    const double peak = test::peakColourOf(camera), noise = test::rmse(camera, camera2), error = test::rmse(moving, camera);
    std::printf("%s %s: velocity vs camera blur RMSE %.5f, seed noise %.5f, peak %.4f, vs still %.5f\n", c.technique.c_str(),
                c.sets.empty() ? "" : c.sets.front().c_str(), error, noise, peak, test::rmse(moving, still));
    ASSERT_GT(peak, 0.02);
    EXPECT_LT(error, 1.5 * noise + 0.01 * peak);
    EXPECT_GT(test::rmse(moving, still), 4 * (noise + 0.01 * peak));  // the blur is there to be matched
}

}  // namespace

TEST(VolumeMotionScatter, SinglescatterCachedVelocityBlurEqualsCameraBlur) {
    expectVelocityBlurEqualsCameraBlur({"volume.singlescatter", {"step=0.25"}, 32});
}

TEST(VolumeMotionScatter, SinglescatterRatioVelocityBlurEqualsCameraBlur) {
    expectVelocityBlurEqualsCameraBlur({"volume.singlescatter", {"estimator=ratio", "step=0.25"}, 32});
}

TEST(VolumeMotionScatter, PathtraceVelocityBlurEqualsCameraBlur) {
    expectVelocityBlurEqualsCameraBlur({"mesh.pathtrace", {"max_depth=2"}, 64});
}

// Majorants padded by the reach: a blob that leaves its bricks within the
// shutter still renders without bias. Thin, so that scattered light adds:
// the blurred image's total light is the still one's. The camera sees the
// whole path (x from -0.375 to 1.375 at 3 units: a 56 degree view). The
// path tracer's totals are noisy (few collisions in a thin medium), so its
// means over seeds are compared within three standard errors.
TEST(VolumeMotionScatter, PathtraceMajorantsCoverWhereTheVolumeMoves) {
    test::TempDir dir;
    test::writeBlob(dir / "blob.vdb", {24, 0, 0}, 0.05f);  // 32 voxels per frame: four bricks
    const test::BlobLook look = test::scatteringLook();
    // The scene file is written anew for each render (one name, two shutters).
    const auto render = [&](const char* shutter, const BlurCase& c, std::uint64_t seed) {
        return renderWith(test::movingBlobScene(dir, look, shutter, "", 56), c.technique, c.sets, c.spp, seed);
    };
    const BlurCase pathtrace{"mesh.pathtrace", {"max_depth=1"}, 64};
    Stats m, s;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        m.add(totalOf(render("[0, 1]", pathtrace, seed)));
        s.add(totalOf(render("[0, 0]", pathtrace, seed)));
    }
    EXPECT_NEAR(m.mean(), s.mean(), 3 * std::sqrt(m.varianceOfMean() + s.varianceOfMean()) + 0.01 * s.mean());
    EXPECT_GT(s.mean(), 0.0);
    const BlurCase single{"volume.singlescatter", {"step=0.25"}, 32};
    const Image singleMoving = render("[0, 1]", single, 1);
    const Image singleStill = render("[0, 0]", single, 1);
    EXPECT_NEAR(totalOf(singleMoving), totalOf(singleStill), 0.04 * totalOf(singleStill));
    EXPECT_LT(test::peakColourOf(singleMoving), 0.7 * test::peakColourOf(singleStill));
}

TEST(VolumeMotionScatter, SameImageOnAnyThreadCount) {
    test::TempDir dir;
    test::writeBlob(dir / "blob.vdb", {6, 3, 0}, 0.5f, true);
    const std::string scene = test::movingBlobScene(dir, test::scatteringLook());
    for (const BlurCase& c : {BlurCase{"volume.singlescatter", {}, 4}, BlurCase{"volume.singlescatter", {"estimator=ratio"}, 4},
                              BlurCase{"mesh.pathtrace", {}, 4}}) {
        const Image one = renderWith(scene, c.technique, c.sets, c.spp, 1, 1);
        const Image two = renderWith(scene, c.technique, c.sets, c.spp, 1, 2);
        EXPECT_EQ(compareImages(one, two).overall.maxAbs, 0.0) << c.technique;
    }
}

