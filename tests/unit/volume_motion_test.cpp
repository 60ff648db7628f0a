// Velocity motion blur: a blob translating by its velocity grid against the
// static blob seen by a camera moving the other way (the same shutter
// samples, so within the march's discretisation), bounds padded by the
// reach, a closed shutter keeping the volume still, one-line errors, and
// absurd velocities staying finite.
#include <gtest/gtest.h>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "core/scene/scene.hpp"
#include "core/volume/volume_grids.hpp"
#include "tests/support/moving_blob.hpp"
#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;

namespace {

using test::writeBlob;

std::string movingScene(const test::TempDir& dir, const std::string& shutter = "[0, 1]", const std::string& extra = "") {
    return test::movingBlobScene(dir, test::transferFunctionLook(), shutter, extra);
}

std::string movingCameraScene(const test::TempDir& dir, double velocityX) {
    return test::movingCameraBlobScene(dir, test::transferFunctionLook(), velocityX);
}

double alphaSum(const Image& img) {
    double sum = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) sum += img.at(x, y, 3);
    return sum;
}

double peakOf(const Image& img, int c) {
    double m = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) m = std::max(m, double(img.at(x, y, c)));
    return m;
}

}  // namespace

// 18 world units per second at 24 fps over a one-frame shutter: the blob
// (sigma 0.125) sweeps 0.75 across the image. Both renders take the same
// 64 shutter times per pixel, so they differ only by where the march's
// samples fall on the grid: within 1% of the peak, while the blur itself
// moves pixels by a third of it or more.
TEST(VolumeMotion, VelocityBlurEqualsCameraBlurTheOtherWay) {
    test::TempDir dir;
    writeBlob(dir / "blob.vdb", {18, 0, 0});
    const std::vector<std::string> sets{"step=0.25"};
    const Image moving = test::render(movingScene(dir), "48x32", sets, "volume.raymarch", 0, 64).image;
    RenderRequest r;  // at frame 0, between the camera's keys
    r.input = movingCameraScene(dir, 18), r.resolution = Resolution{48, 32}, r.sets = sets, r.technique = "volume.raymarch", r.spp = 64, r.frame = 0;
    const Image camera = renderToImage(r).image;
    const Image still = test::render(movingScene(dir, "[0, 0]"), "48x32", sets, "volume.raymarch", 0, 64).image;
    const double peak = peakOf(camera, 3);
    ASSERT_GT(peak, 0.05);
    EXPECT_LT(test::rmse(moving, camera), 0.01 * peak);
    EXPECT_GT(compareImages(moving, still).overall.maxAbs, 0.3 * peak);  // the blur is there to be matched
}

// A blob that leaves its own box within the shutter: the box is padded by
// the reach, so none of it is cut away (32 voxels: skip_empty=auto does
// not skip). Thin enough that opacity adds, the
// blurred image's total alpha is the still one's.
TEST(VolumeMotion, BoundsArePaddedByTheReach) {
    test::TempDir dir;
    writeBlob(dir / "blob.vdb", {24, 0, 0}, 0.05f);  // 32 voxels per frame, the blob is 25 across
    const Scene s = loadScene(movingScene(dir));
    ASSERT_TRUE(s.volumesMove());
    EXPECT_NEAR(s.volumes[0].maxMotion, 32.0, 1e-3);
    EXPECT_NEAR(s.volumes[0].motionReach, 32.0, 1e-3);
    EXPECT_EQ(s.volumes[0].activeBox.max().x(), 12 + 32);
    const Image moving = test::render(movingScene(dir), "96x32", {"step=0.25"}, "volume.raymarch", 0, 16).image;
    const Image still = test::render(movingScene(dir, "[0, 0]"), "96x32", {"step=0.25"}, "volume.raymarch", 0, 16).image;
    EXPECT_NEAR(alphaSum(moving), alphaSum(still), 0.02 * alphaSum(still));
    EXPECT_LT(peakOf(moving, 3), 0.7 * peakOf(still, 3));
}

// skip_empty dilates the moving volume's occupancy by its reach: the same
// image with and without it.
TEST(VolumeMotion, EmptySpaceSkippingSeesWhereTheVolumeMoves) {
    test::TempDir dir;
    writeBlob(dir / "blob.vdb", {12, 0, 0});
    const std::string scene = movingScene(dir);
    const Image skipping = test::render(scene, "32x24", {"skip_empty=true"}, "volume.raymarch", 0, 16).image;
    const Image full = test::render(scene, "32x24", {"skip_empty=false"}, "volume.raymarch", 0, 16).image;
    EXPECT_LT(compareImages(skipping, full).overall.maxAbs, 1e-6);
}

TEST(VolumeMotion, AClosedShutterKeepsTheVolumeStill) {
    test::TempDir dir;
    writeBlob(dir / "blob.vdb", {6, 0, 0});
    const Scene closed = loadScene(movingScene(dir, "[0, 0]"));
    EXPECT_FALSE(closed.volumesMove());
    EXPECT_NE(closed.volumes[0].grids.find("velocity=vel"), std::string::npos) << closed.volumes[0].grids;
    // A bare .vdb has no shutter: its velocity is not even read.
    const Scene bare = loadScene((dir / "blob.vdb").string());
    EXPECT_FALSE(bare.volumesMove());
    EXPECT_EQ(bare.volumes[0].grids, "density=density");
}

TEST(VolumeMotion, SameImageOnAnyThreadCount) {
    test::TempDir dir;
    writeBlob(dir / "blob.vdb", {6, 3, 0}, 0.5f, true);
    const std::string scene = movingScene(dir);
    const Image one = test::render(scene, "24x24", {}, "volume.raymarch", 1, 8).image;
    const Image two = test::render(scene, "24x24", {}, "volume.raymarch", 2, 8).image;
    EXPECT_EQ(compareImages(one, two).overall.maxAbs, 0.0);
}

TEST(VolumeMotion, WrongSettingsAreOneLineErrors) {
    test::TempDir dir;
    writeBlob(dir / "blob.vdb", {6, 0, 0});
    const auto sceneWith = [&](const std::string& volume) {
        test::writeText(dir / "s.json", R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "shutter": [-0.25, 0.25]}, "volumes": [{"file": "blob.vdb", )" +
                                            volume + "}]}");
        return test::errorOf([&] { loadScene((dir / "s.json").string()); });
    };
    EXPECT_NE(sceneWith(R"("motion": {"fps": 24})").find("motion settings need a velocity grid"), std::string::npos);
    EXPECT_NE(sceneWith(R"("grids": {"velocity": "density"})").find("the velocity grid 'density' holds float values; velocity needs a vec3s grid"),
              std::string::npos);
    EXPECT_NE(sceneWith(R"("grids": {"velocity": "v"})").find("no grid named 'v' for velocity (grids: density, vel)"), std::string::npos);
    EXPECT_NE(sceneWith(R"("grids": {"velocity": "vel"}, "motion": {"fps": 0})").find("motion.fps = 0 is outside"), std::string::npos);
    const std::string e = test::errorOf([&] { test::render(movingScene(dir), "8x8", {}, "lighting.vpl_deferred"); });
    EXPECT_NE(e.find("lighting.vpl_deferred does not blur volumes by their velocity"), std::string::npos) << e;
    const std::string alternatives = e.substr(e.find("render it with "));  // from the registry's blur flags
    for (const char* able : {"volume.raymarch", "volume.singlescatter", "volume.preint", "volume.adaptive3d", "mesh.pathtrace"})
        EXPECT_NE(alternatives.find(able), std::string::npos) << e;
    EXPECT_EQ(alternatives.find("lighting."), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

// The slice techniques blur a moving volume as volume.raymarch does (whose
// blur equals camera blur, above): the same blurred picture within their
// slicing's difference from the march, while the blur moves pixels by far
// more. adaptive3d renders spp passes at shutter times, preint one time per
// camera sample.
TEST(VolumeMotion, SliceTechniquesBlurAsRaymarchDoes) {
    test::TempDir dir;
    writeBlob(dir / "blob.vdb", {18, 0, 0});
    const Image march = test::render(movingScene(dir), "48x32", {"step=0.25"}, "volume.raymarch", 0, 64).image;
    const double peak = peakOf(march, 3);
    ASSERT_GT(peak, 0.05);
    for (const char* t : {"volume.preint", "volume.adaptive3d"}) {
        const RenderOutcome moving = test::render(movingScene(dir), "48x32", {"spacing=0.25"}, t, 0, 64);
        const Image still = test::render(movingScene(dir, "[0, 0]"), "48x32", {"spacing=0.25"}, t, 0, 64).image;
        EXPECT_LT(test::rmse(moving.image, march), 0.01 * peak) << t;
        EXPECT_GT(compareImages(moving.image, still).overall.maxAbs, 0.3 * peak) << t;
        if (std::string(t) == "volume.adaptive3d") EXPECT_EQ(moving.counters.at("shutter.passes"), 64);
    }
}

// A fast blob (32 voxels per frame) seen through adaptive3d's oracle: the
// field is padded by the reach, so skipping through what was empty space
// never passes the moved blob; the image is the one the minimum oracle
// (which samples every slice) gives at the same shutter times.
TEST(VolumeMotion, AdaptiveSkippingSeesWhereTheVolumeMoves) {
    test::TempDir dir;
    writeBlob(dir / "blob.vdb", {24, 0, 0});
    const std::string scene = movingScene(dir);
    const Image minimum = test::render(scene, "64x32", {"oracle=minimum"}, "volume.adaptive3d", 0, 8).image;
    const double peak = peakOf(minimum, 3);
    for (const char* oracle : {"gradient_alpha", "majorant", "vdb_topology"}) {
        const Image skipping = test::render(scene, "64x32", {std::string("oracle=") + oracle}, "volume.adaptive3d", 0, 8).image;
        EXPECT_LT(compareImages(skipping, minimum).overall.maxAbs, 0.02 * peak) << oracle;
    }
}

TEST(VolumeMotion, SliceTechniquesGiveTheSameImageOnAnyThreadCount) {
    test::TempDir dir;
    writeBlob(dir / "blob.vdb", {6, 3, 0}, 0.5f, true);
    const std::string scene = movingScene(dir);
    for (const char* t : {"volume.preint", "volume.adaptive3d"}) {
        const Image one = test::render(scene, "24x24", {}, t, 1, 4).image;
        const Image two = test::render(scene, "24x24", {}, t, 2, 4).image;
        EXPECT_EQ(compareImages(one, two).overall.maxAbs, 0.0) << t;
    }
}

// Huge and non-finite velocities: the reach is capped, NaN moves nothing,
// and no NaN or Inf reaches the image.
TEST(VolumeMotion, AbsurdVelocitiesStayFinite) {
    test::TempDir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const openvdb::Vec3s v : {openvdb::Vec3s(1e30f, 0, 0), openvdb::Vec3s(nan, 0, 0), openvdb::Vec3s(1e-30f, 0, 0)}) {
        writeBlob(dir / "blob.vdb", v, 0.5f, true);
        const Scene s = loadScene(movingScene(dir));
        for (const Volume& vol : s.volumes) EXPECT_LE(vol.motionReach, kMaxMotionReach);
        const Image img = test::render(movingScene(dir), "8x8", {"skip_empty=false"}, "volume.raymarch", 0, 2).image;
        for (int y = 0; y < img.height(); ++y)
            for (int x = 0; x < img.width(); ++x)
                for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(img.at(x, y, c))) << v;
    }
}

// The example the docs show: the Gaffer smoke under its swirl velocity
// (data/smoke_small_swirl.vdb, resampled from voxel size 6 to 1.5).
TEST(VolumeMotion, TheSmokeExampleMoves) {
    const Scene s = loadScene(std::string(WEFT_SOURCE_DIR) + "/scenes/smoke_motion.json");
    ASSERT_TRUE(s.volumesMove());
    const Volume& v = s.volumes[0];
    EXPECT_EQ(v.motion->transform(), v.grid->transform());
    EXPECT_NE(v.grids.find("velocity=vel ("), std::string::npos) << v.grids;
    // The swirl's fastest voxel: 6 rad/s at about 30 units out and the
    // 40 units/s rise, x velocity_scale 3 / 24 fps / voxel 1.5: tens of voxels.
    EXPECT_GT(v.maxMotion, 10.0);
    EXPECT_LT(v.maxMotion, 100.0);
    EXPECT_NEAR(v.motionReach, 0.5 * v.maxMotion, 1e-9);
}
