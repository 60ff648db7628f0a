// Scene files: positions of values for file:line:column errors, strict keys,
// and the values a scene sets reaching the Scene.
#include <gtest/gtest.h>

#include "core/base/error.hpp"
#include "core/base/json_doc.hpp"
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
    EXPECT_EQ(*s.render.width, 64);
    EXPECT_EQ(*s.render.spp, 4);
    EXPECT_EQ(s.render.params.at("step"), "0.25");
    EXPECT_EQ(s.render.params.at("jitter"), "true");
}

TEST(SceneLoader, ErrorsPointAtFileLineColumn) {
    EXPECT_EQ(sceneError("{\"volumes\": [{\"procedural\": \"sphere\", \"resolutoin\": 8}]}"),
              "s.json:1:39: unknown key 'resolutoin' in volume; valid keys: file, grid, procedural, resolution, seed, transfer_function");
    EXPECT_EQ(sceneError("{\n\"camera\": {\"fov\": 200}}"), "s.json:2:19: camera.fov = 200 is outside [0.01, 179]");
    EXPECT_EQ(sceneError("{\"volumes\": [{\"procedural\": \"torus\"}]}"),
              "s.json:1:29: unknown procedural volume 'torus' (known: sphere|cloud)");
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
