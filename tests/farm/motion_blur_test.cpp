// Motion blur that follows the frame: a keyed camera moves while the shutter
// (camera.shutter, in frames relative to the frame rendered) is open, and
// every camera sample takes its own time in that interval.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "core/scene/camera.hpp"
#include "core/image/io/image_io.hpp"
#include "tests/support/test_support.hpp"

using namespace weft::test;
namespace fs = std::filesystem;

namespace {

std::string s(const fs::path& p) { return p.string(); }

weft::Image load(const fs::path& p, weft::Metadata* md = nullptr) { return weft::readImage(p.string(), md); }

bool samePixels(const weft::Image& a, const weft::Image& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(float)) == 0;
}

double rmse(const weft::Image& a, const std::vector<double>& b) {
    double sum = 0;
    for (std::size_t i = 0; i < b.size(); ++i) sum += (a.data()[i] - b[i]) * (a.data()[i] - b[i]);
    return std::sqrt(sum / double(b.size()));
}

// A dense sphere the camera pans across: 3 units from frame 0 to frame 4.
const char* kPanKeys = R"([{"frame": 0, "eye": [-1.5, 0, 4], "target": [-1.5, 0, 0]},
                           {"frame": 4, "eye": [1.5, 0, 4], "target": [1.5, 0, 0]}])";

std::string panScene(const std::string& cameraExtra) {
    return R"({"volumes": [{"procedural": "sphere", "resolution": 16}],
               "camera": {"fov": 40, "keys": )" + std::string(kPanKeys) + cameraExtra + R"(},
               "render": {"resolution": [32, 16]}})";
}

// A fixed camera where the pan puts it at (fractional) frame f.
std::string instantScene(double f) {
    const double x = -1.5 + 3.0 * f / 4.0;
    return R"({"volumes": [{"procedural": "sphere", "resolution": 16}],
               "camera": {"fov": 40, "eye": [)" + std::to_string(x) + R"(, 0, 4], "target": [)" + std::to_string(x) +
           R"(, 0, 0]}, "render": {"resolution": [32, 16]}})";
}

TEST(MotionBlur, CameraPathInterpolatesFractionalFramesAndShutterTimesFollowTheFrame) {
    weft::CameraPath path;
    weft::Camera a, b;
    a.eye = {0, 0, 4}, b.eye = {4, 0, 4};
    path.keys = {{10, a}, {12, b}};
    EXPECT_DOUBLE_EQ(path.at(10.5).eye.x(), 1.0);
    EXPECT_DOUBLE_EQ(path.at(9).eye.x(), 0.0);                 // held before the first key
    EXPECT_DOUBLE_EQ(path.at(13).eye.x(), 4.0);                // and after the last
    EXPECT_DOUBLE_EQ(path.at(std::nan("")).eye.x(), 0.0);      // never NaN
    const weft::Shutter shutter{-0.25, 0.25};
    EXPECT_DOUBLE_EQ(shutter.frameTime(1001, 0.0), 1000.75);
    EXPECT_DOUBLE_EQ(shutter.frameTime(1001, 0.5), 1001.0);
    EXPECT_DOUBLE_EQ(shutter.frameTime(1002, 1.0), 1002.25);
}

// The blurred frame converges to the mean of the instants the shutter spans.
TEST(MotionBlur, BlurredFrameIsTheMeanOfTheInstantsItSpans) {
    TempDir dir;
    writeText(dir / "pan.json", panScene(R"(, "shutter": [-0.5, 0.5])"));
    const std::string opts = " --spp 64 --set pattern=jittered --threads 2 ";
    auto r = runWeft("render " + s(dir / "pan.json") + " --frames 2" + opts + "-o " + s(dir / "blur.#.exr"));
    ASSERT_EQ(r.status, 0) << r.output;
    weft::Metadata md;
    const weft::Image blur = load(dir / "blur.0002.exr", &md);
    const int instants = 16;
    std::vector<double> mean(blur.data().size(), 0.0);
    for (int k = 0; k < instants; ++k) {
        const fs::path scene = dir / ("i" + std::to_string(k) + ".json"), out = dir / ("i" + std::to_string(k) + ".exr");
        writeText(scene, instantScene(1.5 + (k + 0.5) / instants));
        ASSERT_EQ(runWeft("render " + s(scene) + opts + "-o " + s(out)).status, 0);
        const weft::Image img = load(out);
        for (std::size_t i = 0; i < mean.size(); ++i) mean[i] += img.data()[i] / instants;
    }
    writeText(dir / "still.json", instantScene(2.0));
    ASSERT_EQ(runWeft("render " + s(dir / "still.json") + opts + "-o " + s(dir / "still.exr")).status, 0);
    const weft::Image still = load(dir / "still.exr");
    std::vector<double> stillValues(still.data().begin(), still.data().end());
    const double toMean = rmse(blur, mean), toStill = rmse(blur, stillValues);
    EXPECT_GT(toStill, 0.02) << "the pan should blur the sphere visibly: " << toMean;
    EXPECT_LT(toMean, 0.2 * toStill) << toMean << " vs " << toStill;
    bool shutterRecorded = false;
    for (const auto& [k, v] : md) shutterRecorded |= k == "weft:shutter" && v == "-0.5 0.5";
    EXPECT_TRUE(shutterRecorded);
}

// Sample times are frame times: frame 11 with a shutter [-1, 0] is frame 10
// with [0, 1], bit for bit, and consecutive frames are blurred differently.
TEST(MotionBlur, TimeSamplesAreFrameTimes) {
    TempDir dir;
    writeText(dir / "after.json", panScene(R"(, "shutter": [0, 1])"));
    writeText(dir / "before.json", panScene(R"(, "shutter": [-1, 0])"));
    for (const char* technique : {"volume.raymarch", "mesh.pathtrace"}) {
        if (std::string(technique) == "mesh.pathtrace") {  // a lit quad for the path tracer
            const std::string quad = std::string(R"({"meshes": [{"file": ")") + s(dir / "quad.obj") + R"("}],
                "camera": {"fov": 40, "keys": )" + kPanKeys;
            writeText(dir / "quad.obj", "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nusemtl glow\nf 1 2 3 4\n");
            writeText(dir / "quad.mtl", "newmtl glow\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
            writeText(dir / "after.json", quad + R"(, "shutter": [0, 1]}, "render": {"resolution": [32, 16]}})");
            writeText(dir / "before.json", quad + R"(, "shutter": [-1, 0]}, "render": {"resolution": [32, 16]}})");
        }
        const std::string opts = std::string(" --technique ") + technique + " --spp 4 --seed 9 ";
        ASSERT_EQ(runWeft("render " + s(dir / "after.json") + " --frames 1-2" + opts + "-o " + s(dir / "a.#.exr")).status, 0);
        ASSERT_EQ(runWeft("render " + s(dir / "before.json") + " --frames 2-3" + opts + "-o " + s(dir / "b.#.exr")).status, 0);
        EXPECT_TRUE(samePixels(load(dir / "a.0001.exr"), load(dir / "b.0002.exr"))) << technique;
        EXPECT_TRUE(samePixels(load(dir / "a.0002.exr"), load(dir / "b.0003.exr"))) << technique;
        EXPECT_FALSE(samePixels(load(dir / "a.0001.exr"), load(dir / "a.0002.exr"))) << technique;
    }
}

TEST(MotionBlur, ShutterErrorsAndTechniquesThatRenderOneInstant) {
    TempDir dir;
    writeText(dir / "reversed.json", panScene(R"(, "shutter": [0.5, -0.5])"));
    auto r = runWeft("render " + s(dir / "reversed.json") + " -o " + s(dir / "o.exr"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("camera.shutter must be [open, close]"), std::string::npos) << r.output;
    writeText(dir / "pan.json", panScene(R"(, "shutter": [-0.25, 0.25])"));
    r = runWeft("render " + s(dir / "pan.json") + " --technique volume.preint --frames 2 -o " + s(dir / "o.#.exr"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("volume.preint renders one instant"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "o.0002.exr"));
    // A camera that holds still over the shutter needs no motion blur: any technique, the instant's image.
    writeText(dir / "held.json", panScene(R"(, "shutter": [-0.25, 0.25])"));
    ASSERT_EQ(runWeft("render " + s(dir / "held.json") + " --technique volume.preint --frames 9 -o " + s(dir / "h.#.exr")).status, 0);
    writeText(dir / "end.json", instantScene(4.0));
    ASSERT_EQ(runWeft("render " + s(dir / "end.json") + " --technique volume.preint -o " + s(dir / "end.exr")).status, 0);
    EXPECT_TRUE(samePixels(load(dir / "h.0009.exr"), load(dir / "end.exr")));
}

}  // namespace
