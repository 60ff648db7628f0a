// volume.raymarch against closed forms, its own options, and at extremes.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/error.hpp"
#include "core/scene/scene.hpp"
#include "core/volume/volume.hpp"
#include "plugins/volume_raymarch/volume_march.hpp"
#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/vdb_fixtures.hpp"

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
    const RenderOutcome full = render("builtin:cloud", "48x48", {"step=0.5", "skip_empty=false"});
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

namespace {

// A volume of `grid` under a transfer function transparent at 0 and opaque above.
Volume volumeOf(openvdb::FloatGrid::Ptr grid) {
    Volume v;
    v.grid = grid;
    v.tf = TransferFunction(0, 1, {{0, {1, 1, 1}, 0}, {1, {1, 1, 1}, 1}});
    computeStatistics(v);
    return v;
}

}  // namespace

// skip_empty=auto skips where the cells left to march fill at most 3/4 of
// the active box and the background is transparent; otherwise it marches all.
TEST(Raymarch, SkipEmptyAutoDecidesBySparsityAndTransparency) {
    initVdb();
    auto dense = openvdb::FloatGrid::create(0.0f);
    dense->tree().fill(openvdb::CoordBBox({0, 0, 0}, {31, 31, 31}), 0.5f, true);
    dense->tree().voxelizeActiveTiles();
    EXPECT_FALSE(emptySpacePays({volumeOf(dense)}));

    auto sparse = openvdb::FloatGrid::create(0.0f);  // two leaves at opposite corners of a 200^3 box
    sparse->tree().setValue(openvdb::Coord(0, 0, 0), 0.5f);
    sparse->tree().setValue(openvdb::Coord(200, 200, 200), 0.5f);
    EXPECT_TRUE(emptySpacePays({volumeOf(sparse)}));
    EXPECT_TRUE(emptySpacePays({volumeOf(dense), volumeOf(sparse)}));  // filled and boxed voxels add over the volumes

    auto hidden = sparse->deepCopy();  // an inactive 128^3 tile, visible: it is marched, and skipping still pays
    hidden->tree().addTile(2, openvdb::Coord(4096, 0, 0), 0.8f, false);
    EXPECT_TRUE(emptySpacePays({volumeOf(hidden)}));
    auto inactiveVoxel = sparse->deepCopy();  // one visible inactive voxel is marched, and skipping still pays
    inactiveVoxel->tree().setValueOff(openvdb::Coord(1, 0, 0), 0.8f);
    EXPECT_TRUE(emptySpacePays({volumeOf(inactiveVoxel)}));

    Volume fog = volumeOf(sparse);  // opaque at the background: nothing may be skipped
    fog.tf = TransferFunction(0, 1, {{0, {1, 1, 1}, 0.1}});
    EXPECT_FALSE(emptySpacePays({fog}));
    EXPECT_FALSE(emptySpacePays({}));
}

// Whatever auto decides, the image is the one of the full march.
TEST(Raymarch, SkipEmptyAutoNeverChangesTheImage) {
    for (const char* scene : {"builtin:cloud", "builtin:sphere"}) {
        const RenderOutcome full = render(scene, "32x32", {"step=0.5", "skip_empty=false"});
        const RenderOutcome automatic = render(scene, "32x32", {"step=0.5"});
        EXPECT_EQ(full.image.data(), automatic.image.data()) << scene;
        EXPECT_LE(automatic.counters.at("volume.samples"), full.counters.at("volume.samples")) << scene;
    }
}

// Cells whose values the transfer function hides are skipped like empty
// space: the same cloud marches fewer samples where more of its values are
// transparent, and each image is its full march's.
TEST(Raymarch, SkipEmptySkipsWhatTheTransferFunctionHides) {
    test::TempDir dir;
    const auto cloud = [&](const std::string& name, const std::string& points) {
        test::writeText(dir / name, R"({"volumes": [{"procedural": "cloud", "resolution": 32, "transfer_function": {"points": [)" +
                                        points + "]}}]}");
        return (dir / name).string();
    };
    const std::string all = cloud("all.json", R"({"s": 0, "extinction": 0}, {"s": 1, "extinction": 0.5})");
    const std::string dense = cloud("dense.json", R"({"s": 0, "extinction": 0}, {"s": 0.5, "extinction": 0}, {"s": 1, "extinction": 0.5})");
    std::int64_t samples[2];
    int i = 0;
    for (const std::string& scene : {all, dense}) {
        const RenderOutcome full = render(scene, "32x32", {"step=0.5", "ert=1", "skip_empty=false"});
        const RenderOutcome skip = render(scene, "32x32", {"step=0.5", "ert=1", "skip_empty=true"});  // no ERT: skipping alone
        EXPECT_EQ(full.image.data(), skip.image.data()) << scene;
        samples[i++] = skip.counters.at("volume.samples");
    }
    EXPECT_LT(double(samples[1]), 0.95 * double(samples[0]));  // 0.91 measured: the HDDA skips by whole leaves
}

// The runs of a sweep and the frames of a sequence share one skipper per set
// of volumes; another transfer function, another set or a moving volume does not.
TEST(Raymarch, SkippersAreSharedBetweenRendersOfTheSameVolumes) {
    initVdb();
    clearSkipperCache();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->tree().fill(openvdb::CoordBBox({0, 0, 0}, {7, 7, 7}), 0.5f, true);
    const Volume v = volumeOf(grid);
    const SharedSkipper first = sharedEmptySpaceSkipper({v});
    const SharedSkipper second = sharedEmptySpaceSkipper({v});
    EXPECT_FALSE(first.reused);
    ASSERT_TRUE(second.reused);
    EXPECT_EQ(first.skipper.get(), second.skipper.get());
    Volume otherTf = v;
    otherTf.tf = TransferFunction(0, 1, {{0, {1, 1, 1}, 0}, {1, {1, 1, 1}, 2}});
    EXPECT_FALSE(sharedEmptySpaceSkipper({otherTf}).reused);
    EXPECT_FALSE(sharedEmptySpaceSkipper({v, otherTf}).reused);
    Volume moving = v;
    moving.motion = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    EXPECT_FALSE(sharedEmptySpaceSkipper({moving}).reused);
    EXPECT_FALSE(sharedEmptySpaceSkipper({moving}).reused);
}

// Each frame loads its volume again: an unchanged file finds the skipper
// its first load built, and the frames' images equal fresh renders'.
TEST(Raymarch, AFreshLoadOfTheSameFileFindsItsSkipper) {
    clearSkipperCache();
    test::TempDir dir;
    test::writeProceduralVdb(dir / "cloud.vdb", "cloud", 24);
    const std::string path = (dir / "cloud.vdb").string();
    EXPECT_FALSE(sharedEmptySpaceSkipper(loadScene(path).volumes).reused);
    EXPECT_TRUE(sharedEmptySpaceSkipper(loadScene(path).volumes).reused);
    const Image shared = test::render(path, "32x24", {"skip_empty=true"}, "volume.raymarch").image;
    clearSkipperCache();
    const Image fresh = test::render(path, "32x24", {"skip_empty=true"}, "volume.raymarch").image;
    EXPECT_EQ(shared.data(), fresh.data());
}
