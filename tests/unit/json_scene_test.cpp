// Scene files: positions of values for file:line:column errors, strict keys,
// and the values a scene sets reaching the Scene.
#include <gtest/gtest.h>

#include "core/base/error.hpp"
#include "core/base/files/json_doc.hpp"
#include "core/scene/scene.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;

namespace {

std::string sceneError(const std::string& text) {
    test::TempDir dir;
    test::writeText(dir / "s.json", text);
    try {
        loadScene((dir / "s.json").string(), 1.0);
    } catch (const Error& e) {
        const std::string msg = e.what();
        return msg.substr(msg.find("s.json"));
    }
    return "";
}

}  // namespace

TEST(JsonDoc, PositionsOfKeysAndValues) {
    const JsonDoc doc = JsonDoc::parse("{\n  \"a\": 1,\n  \"list\": [ true, {\"k\": \"v\"} ]\n}", "f.json");
    EXPECT_EQ(doc.where("/a"), "f.json:2:8");
    EXPECT_EQ(doc.where("/a#key"), "f.json:2:3");
    EXPECT_EQ(doc.where("/list/0"), "f.json:3:13");
    EXPECT_EQ(doc.where("/list/1"), "f.json:3:19");
    EXPECT_EQ(doc.where("/list/1/k"), "f.json:3:25");
    EXPECT_EQ(doc.root()["list"][1]["k"], "v");
}

TEST(JsonDoc, SyntaxErrorNamesLineAndColumn) {
    try {
        JsonDoc::parse("{\n  \"a\": [1, 2,,]\n}", "bad.json");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.json:2:14: JSON syntax error"), std::string::npos) << e.what();
    }
}

// A 401-digit number is an error in weft's words, with the number cut short
// (the library's "[json.exception.out_of_range.406]" and the digits echoed in
// full are not).
TEST(JsonDoc, HugeNumberIsNamedShortly) {
    const std::string digits = "1" + std::string(400, '0');
    const std::string msg = test::errorOf([&] { JsonDoc::parse("{\"fov\": " + digits + "}", "big.json"); });
    ASSERT_FALSE(msg.empty()) << "no error";
    EXPECT_NE(msg.find("big.json:1:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("number too large for a double"), std::string::npos) << msg;
    EXPECT_NE(msg.find("(401 characters)"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("json.exception"), std::string::npos) << msg;
    EXPECT_LT(msg.size(), 160u) << msg;
}

TEST(JsonDoc, SyntaxErrorHasNoLibraryPrefix) {
    const std::string msg = test::errorOf([] { JsonDoc::parse("{\"a\": tru}", "t.json"); });
    ASSERT_FALSE(msg.empty()) << "no error";
    EXPECT_EQ(msg.find("json.exception"), std::string::npos) << msg;
}

TEST(SceneLoader, ReadsCameraVolumesLightsAndRenderSettings) {
    test::TempDir dir;
    test::writeText(dir / "s.json", R"({
      "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "fov": 30},
      "volumes": [{"procedural": "sphere", "resolution": 16,
                   "transfer_function": {"range": [0, 2], "points": [{"s": 0, "extinction": 0}, {"s": 1, "color": [1, 0.5, 0], "extinction": 4}]}}],
      "lights": [{"type": "directional", "direction": [0, -2, 0], "intensity": 3}],
      "render": {"technique": "volume.raymarch", "resolution": [64, 32], "spp": 4, "seed": 9, "params": {"step": 0.25, "jitter": true}}
    })");
    const Scene s = loadScene((dir / "s.json").string());
    EXPECT_DOUBLE_EQ(s.camera.fovY, 30.0);
    ASSERT_EQ(s.volumes.size(), 1u);
    EXPECT_DOUBLE_EQ(s.volumes[0].tf.rangeMax(), 2.0);
    EXPECT_NEAR(s.volumes[0].tf.lookup(2.0f).extinction, 4.0f, 1e-5);
    EXPECT_NEAR(s.volumes[0].tf.lookup(1.0f).g, 0.75f, 1e-3);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_NEAR(s.lights[0].direction.y(), -1.0, 1e-12);  // normalised
    EXPECT_EQ(*s.render.technique, "volume.raymarch");
    EXPECT_EQ(*s.render.resolution, (Resolution{64, 32}));
    EXPECT_EQ(*s.render.spp, 4);
    EXPECT_EQ(*s.render.seed, 9u);
    EXPECT_EQ(s.render.sets, (std::vector<std::string>{"jitter=true", "step=0.25"}));  // JSON objects read in key order
}

TEST(SceneLoader, ErrorsPointAtFileLineColumn) {
    EXPECT_EQ(sceneError("{\"volumes\": [{\"procedural\": \"sphere\", \"resolutoin\": 8}]}"),
              "s.json:1:39: unknown key 'resolutoin' in volume; valid keys: emission, file, grid, grids, medium, motion, procedural, resolution, rotate, scale, seed, transfer_function, translate");
    EXPECT_EQ(sceneError("{\n\"camera\": {\"fov\": 200}}"), "s.json:2:19: camera.fov = 200 is outside [0.01, 179]");
    EXPECT_EQ(sceneError("{\"volumes\": [{\"procedural\": \"torus\"}]}"),
              "s.json:1:29: unknown procedural volume 'torus' (known: sphere|cloud|ct|fire)");
    EXPECT_EQ(sceneError("{\"volumes\": [{}]}"), "s.json:1:14: a volume needs exactly one of 'file' or 'procedural'");
    EXPECT_EQ(sceneError("{\"lights\": [{\"type\": \"spot\"}]}"),
              "s.json:1:22: unknown light type 'spot' (known: directional|point|environment)");
    EXPECT_EQ(sceneError("{\"camera\": {\"eye\": [1, 2]}}"), "s.json:1:20: camera.eye must be an array of 3 numbers");
}

TEST(SceneLoader, VolumeFilesAreRelativeToTheSceneAndErrorsNameThem) {
    const std::string msg = sceneError("{\"volumes\": [{\"file\": \"missing.vdb\"}]}");
    EXPECT_NE(msg.find("s.json:1:23: volume '"), std::string::npos) << msg;
    EXPECT_NE(msg.find("missing.vdb': no such file"), std::string::npos) << msg;
}

TEST(SceneLoader, PlacementComposesWithTheGridTransform) {
    test::TempDir dir;
    test::writeText(dir / "s.json", R"({"volumes": [
        {"procedural": "sphere", "resolution": 16},
        {"procedural": "sphere", "resolution": 16, "scale": [1, 2, 1], "rotate": [0, 0, 90], "translate": [3, 0, 0]}]})");
    const Scene scene = loadScene((dir / "s.json").string(), 1.0);
    ASSERT_EQ(scene.volumes.size(), 2u);
    const BBoxd plain = scene.volumes[0].worldBox(), moved = scene.volumes[1].worldBox();
    // Scaled 2x along y, then turned 90 degrees about z: the long axis lies along x.
    EXPECT_NEAR(moved.extents().x(), 2 * plain.extents().y(), 1e-9);
    EXPECT_NEAR(moved.extents().y(), plain.extents().x(), 1e-9);
    EXPECT_NEAR(moved.getCenter().x() - plain.getCenter().x(), 3.0, 1e-9);
    EXPECT_NEAR(scene.volumes[1].voxelLength(), std::cbrt(2.0) * scene.volumes[0].voxelLength(), 1e-12);
    // The grid is shared, not copied.
    EXPECT_EQ(scene.volumes[1].valueMax, scene.volumes[0].valueMax);
}

TEST(SceneLoader, MediumIsReadAndChecked) {
    test::TempDir dir;
    test::writeText(dir / "s.json", R"({"volumes": [{"procedural": "sphere", "resolution": 8,
        "medium": {"absorb": [0.5, 0.25, 0], "scatter": [2, 2, 2], "g": 0.3}}]})");
    const Scene scene = loadScene((dir / "s.json").string(), 1.0);
    const VolumeMedium& m = scene.volumes[0].medium;
    EXPECT_TRUE(m.fromScene);
    EXPECT_EQ(m.absorb, Vec3d(0.5, 0.25, 0));
    EXPECT_EQ(m.scatter, Vec3d(2, 2, 2));
    EXPECT_DOUBLE_EQ(m.g, 0.3);
    EXPECT_NE(sceneError(R"({"volumes": [{"procedural": "sphere", "medium": {"absorb": [-1, 0, 0]}}]})")
                  .find("medium.absorb must be three numbers >= 0"), std::string::npos);
    EXPECT_NE(sceneError(R"({"volumes": [{"procedural": "sphere", "medium": {"g": 1}}]})").find("medium.g = 1 is outside"),
              std::string::npos);
    EXPECT_NE(sceneError(R"({"volumes": [{"procedural": "sphere", "scale": [1, 0, 1]}]})").find("scale must be positive"),
              std::string::npos);
}

TEST(SceneLoader, PlacementThatOverflowsIsAnError) {
    test::TempDir dir;
    test::writeText(dir / "tri.obj", "v 0 0 0\nv 1e30 0 0\nv 0 1 0\nf 1 2 3\n");
    test::writeText(dir / "s.json", R"({"meshes": [{"file": "tri.obj", "scale": 1e10}]})");
    try {
        loadScene((dir / "s.json").string(), 1.0);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("vertex beyond +-1e+12 scene units"), std::string::npos) << e.what();
    }
}

TEST(SceneLoader, MeshesTakeTheSamePlacement) {
    test::TempDir dir;
    test::writeText(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    test::writeText(dir / "s.json", R"({"meshes": [{"file": "tri.obj", "scale": 2, "rotate": [0, 0, 90], "translate": [0, 0, 5]}]})");
    const Scene scene = loadScene((dir / "s.json").string(), 1.0);
    const BBoxd box = scene.worldBox();
    // (1, 0) -> (2, 0) -> (0, 2); (0, 1) -> (0, 2) -> (-2, 0).
    EXPECT_NEAR(box.min().x(), -2, 1e-6);
    EXPECT_NEAR(box.max().y(), 2, 1e-6);
    EXPECT_NEAR(box.min().z(), 5, 1e-6);
}
