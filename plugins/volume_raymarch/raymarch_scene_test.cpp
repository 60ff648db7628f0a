// volume.raymarch on whole scenes: surfaces behind and inside volumes,
// several volumes, rotated, anisotropic and sheared grids.
#include <gtest/gtest.h>

#include <openvdb/io/File.h>

#include <cmath>
#include <filesystem>

#include "core/volume/volume.hpp"
#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;
using weft::test::render;

namespace {

// A quad facing +z at depth z, 4 x 4 wide, with a material of albedo kd.
void writePlane(const std::filesystem::path& dir, double z, double kd) {
    test::writeText(dir / "plane.mtl", "newmtl m\nKd " + std::to_string(kd) + " " + std::to_string(kd) + " " + std::to_string(kd) + "\n");
    const std::string zs = std::to_string(z);
    test::writeText(dir / "plane.obj", "mtllib plane.mtl\nusemtl m\nv -2 -2 " + zs + "\nv 2 -2 " + zs + "\nv 2 2 " + zs +
                                           "\nv -2 2 " + zs + "\nf 1 2 3 4\n");
}

const char* kCamera = R"("camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 30})";

// White emission, extinction `e` per voxel length at density 1.
std::string whiteTf(double e) {
    return R"("transfer_function": {"points": [{"s": 0, "color": [1, 1, 1], "extinction": 0}, {"s": 1, "color": [1, 1, 1], "extinction": )" +
           std::to_string(e) + "}]}";
}

std::string sceneText(const std::string& volumes, bool plane, const std::string& lights = "[]") {
    return std::string("{") + kCamera + ", \"volumes\": [" + volumes + "]" +
           (plane ? R"(, "meshes": [{"file": "plane.obj"}])" : "") + ", \"lights\": " + lights + "}";
}

std::string writeScene(const test::TempDir& dir, const std::string& name, const std::string& text) {
    test::writeText(dir / name, text);
    return (dir / name).string();
}

double maxAbsDiff(const Image& a, const Image& b) {
    double m = 0;
    for (std::size_t i = 0; i < a.data().size(); ++i) m = std::max(m, double(std::abs(a.data()[i] - b.data()[i])));
    return m;
}

}  // namespace

TEST(RaymarchScene, DiffusePlaneBehindSphereIsCompositedWithTheChordTransmittance) {
    // Sphere of radius 0.4 in 64^3 voxels: the centre ray's chord is 51.2
    // voxels. The plane (albedo 0.5) faces a light along -z of intensity 2:
    // its radiance is 0.5 / pi * 2, seen through the sphere's transmittance.
    test::TempDir dir;
    writePlane(dir.path(), -1.0, 0.5);
    const std::string light = R"([{"type": "directional", "direction": [0, 0, -1], "intensity": 2}])";
    const std::string vol = R"({"procedural": "sphere", "resolution": 64, )" + whiteTf(0.02) + "}";
    const RenderOutcome out = render(writeScene(dir, "s.json", sceneText(vol, true, light)), "33x33", {"step=0.02", "ert=1"});
    const double T = std::exp(-0.02 * 51.2), plane = 0.5 / M_PI * 2.0;
    EXPECT_NEAR(out.image.at(16, 16, 0), (1 - T) + T * plane, 2e-3);
    EXPECT_EQ(out.image.at(16, 16, 3), 1.0f);  // a surface is opaque
    EXPECT_NEAR(out.image.at(0, 0, 1), plane, 1e-5);  // beside the sphere: the plane alone
    EXPECT_EQ(out.counters.at("rays.surface"), 33 * 33);
    EXPECT_EQ(out.counters.at("rays.shadow"), 33 * 33);
}

TEST(RaymarchScene, SurfaceInsideHomogeneousVolumeEndsTheMarchWithAPartialSegment) {
    // Extinction 0.1 per voxel everywhere in the box (also at density 0); the
    // camera sits inside it, a black plane 0.5 ahead: 8 voxels of 1/16.
    test::TempDir dir;
    writePlane(dir.path(), -0.2, 0.0);
    const std::string vol = R"({"procedural": "sphere", "resolution": 16,
        "transfer_function": {"points": [{"s": 0, "color": [1, 1, 1], "extinction": 0.1}]}})";
    const std::string text = std::string(R"({"camera": {"eye": [0, 0, 0.3], "target": [0, 0, -1], "up": [0, 1, 0], "fov": 30},)") +
                             R"("volumes": [)" + vol + R"(], "meshes": [{"file": "plane.obj"}]})";
    const std::string scene = writeScene(dir, "inside.json", text);
    const double expected = 1 - std::exp(-0.1 * 8.0);
    for (const std::string step : {"0.3", "0.7", "3", "64"}) {
        const RenderOutcome out = render(scene, "9x9", {"step=" + step, "ert=1"});
        EXPECT_NEAR(out.image.at(4, 4, 0), expected, 2e-5) << "step " << step;
        EXPECT_EQ(out.image.at(4, 4, 3), 1.0f);
    }
}

TEST(RaymarchScene, TwoCoincidentVolumesAddTheirExtinction) {
    test::TempDir dir;
    const std::string once = R"({"procedural": "cloud", "resolution": 24, )" + whiteTf(0.2) + "}";
    const std::string half = R"({"procedural": "cloud", "resolution": 24, )" + whiteTf(0.1) + "}";
    const std::string one = writeScene(dir, "one.json", sceneText(once, false));
    const std::string two = writeScene(dir, "two.json", sceneText(half + ", " + half, false));
    for (const std::string skip : {"false", "true"}) {
        const RenderOutcome a = render(one, "24x24", {"step=0.5", "skip_empty=" + skip});
        const RenderOutcome b = render(two, "24x24", {"step=0.5", "skip_empty=" + skip});
        EXPECT_LT(maxAbsDiff(a.image, b.image), 1e-5) << "skip_empty=" << skip;
        EXPECT_GT(a.image.at(12, 12, 3), 0.3f);
        EXPECT_EQ(b.counters.at("volume.samples"), 2 * a.counters.at("volume.samples"));
    }
}

TEST(RaymarchScene, RotatedAnisotropicSphereRendersLikeTheUnrotatedOne) {
    // Scale [1, 2, 1] then 90 degrees about z is the sphere stretched along x:
    // the same world density as scale [2, 1, 1], on a grid turned on its side.
    test::TempDir dir;
    const std::string tf = whiteTf(0.015);
    const std::string turned = R"({"procedural": "sphere", "resolution": 64, "scale": [1, 2, 1], "rotate": [0, 0, 90], )" + tf + "}";
    const std::string plain = R"({"procedural": "sphere", "resolution": 64, "scale": [2, 1, 1], )" + tf + "}";
    const RenderOutcome a = render(writeScene(dir, "a.json", sceneText(turned, false)), "33x33", {"step=0.1", "ert=1"});
    const RenderOutcome b = render(writeScene(dir, "b.json", sceneText(plain, false)), "33x33", {"step=0.1", "ert=1"});
    EXPECT_LT(test::rmse(a.image, b.image), 2e-3);
    // Centre chord: 0.8 along z, in voxel lengths cbrt(1 * 2 * 1) / 64.
    const double expected = 1 - std::exp(-0.015 * 0.8 / (std::cbrt(2.0) / 64));
    EXPECT_NEAR(a.image.at(16, 16, 3), expected, 2e-3);
    EXPECT_NEAR(b.image.at(16, 16, 3), expected, 2e-3);
}

TEST(RaymarchScene, SkipEmptyOnAShearedAnisotropicGridGivesTheSameImage) {
    initVdb();
    test::TempDir dir;
    openvdb::FloatGrid::Ptr grid = makeProceduralGrid("cloud", 24, 7);
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.setToScale(openvdb::Vec3d(1.0 / 24, 1.5 / 24, 0.8 / 24));
    m(1, 0) = 0.4 / 24;  // shear: x moves with y
    grid->setTransform(openvdb::math::Transform::createLinearTransform(m));
    grid->setName("density");
    openvdb::io::File((dir / "sheared.vdb").string()).write({grid});
    const std::string vol = R"({"file": "sheared.vdb", "rotate": [20, 35, 0], "scale": [1, 0.8, 1.2], )" + whiteTf(0.15) + "}";
    const std::string scene = writeScene(dir, "sheared.json", sceneText(vol, false));
    const RenderOutcome full = render(scene, "32x32", {"step=0.5"});
    const RenderOutcome skip = render(scene, "32x32", {"step=0.5", "skip_empty=true"});
    EXPECT_EQ(full.image.data(), skip.image.data());
    EXPECT_LT(skip.counters.at("volume.samples"), full.counters.at("volume.samples"));
    EXPECT_GT(full.image.at(16, 16, 3), 0.2f);
}

TEST(RaymarchScene, CombinedSceneIsTheSameForAnyThreadCount) {
    const std::string scene = std::string(WEFT_SOURCE_DIR) + "/scenes/combined/smoke_over_ground.json";
    const RenderOutcome a = render(scene, "64x48", {}, "volume.raymarch", 1);
    const RenderOutcome b = render(scene, "64x48", {}, "volume.raymarch", 2);
    EXPECT_EQ(a.image.data(), b.image.data());
    EXPECT_EQ(a.counters.at("rays.shadow"), b.counters.at("rays.shadow"));
    for (float v : a.image.data()) ASSERT_TRUE(std::isfinite(v));
}

TEST(RaymarchScene, CombinedImageDiffersFromVolumeOnlyAndMeshOnly) {
    test::TempDir dir;
    writePlane(dir.path(), -0.6, 0.8);
    const std::string light = R"([{"type": "point", "position": [0.5, 1, 2], "intensity": 6}])";
    const std::string vol = R"({"procedural": "cloud", "resolution": 24, )" + whiteTf(0.2) + "}";
    const RenderOutcome both = render(writeScene(dir, "both.json", sceneText(vol, true, light)), "24x24", {});
    const RenderOutcome volume = render(writeScene(dir, "vol.json", sceneText(vol, false, light)), "24x24", {});
    const RenderOutcome mesh = render(writeScene(dir, "mesh.json", sceneText("", true, light)), "24x24", {});
    EXPECT_GT(test::rmse(both.image, volume.image), 0.05);
    EXPECT_GT(test::rmse(both.image, mesh.image), 0.05);
    // Where the cloud is clear the plane shows unchanged; in front of it, the cloud dims it.
    EXPECT_NEAR(both.image.at(0, 0, 0), mesh.image.at(0, 0, 0), 1e-6);
    EXPECT_LT(std::abs(both.image.at(12, 12, 0) - (volume.image.at(12, 12, 0) + (1 - volume.image.at(12, 12, 3)) * mesh.image.at(12, 12, 0))), 1e-5);
}

TEST(RaymarchScene, ARayThroughOneOfSeveralVolumesMarchesItAtItsOwnVoxelLength) {
    // A fine and a coarse sphere either side of the camera's axis: no ray
    // meets both, so every pixel is that of the volume it crosses alone
    // (the common step follows the volumes a ray crosses, not the scene's).
    test::TempDir dir;
    const std::string fine = R"({"procedural": "sphere", "resolution": 32, "translate": [0.8, 0, 0], )" + whiteTf(0.05) + "}";
    const std::string coarse = R"({"procedural": "cloud", "resolution": 12, "translate": [-0.8, 0, 0], )" + whiteTf(0.3) + "}";
    auto wide = [](std::string text) { return text.replace(text.find("\"fov\": 30"), 9, "\"fov\": 40"); };
    const RenderOutcome both = render(writeScene(dir, "both.json", wide(sceneText(fine + ", " + coarse, false))), "32x16", {"step=0.7"});
    const RenderOutcome a = render(writeScene(dir, "a.json", wide(sceneText(fine, false))), "32x16", {"step=0.7"});
    const RenderOutcome b = render(writeScene(dir, "b.json", wide(sceneText(coarse, false))), "32x16", {"step=0.7"});
    for (std::size_t i = 0; i < both.image.data().size(); ++i)
        ASSERT_EQ(both.image.data()[i], a.image.data()[i] + b.image.data()[i]) << "value " << i;
    EXPECT_GT(a.image.at(22, 8, 3), 0.3f);
    EXPECT_GT(b.image.at(10, 8, 3), 0.1f);
}
