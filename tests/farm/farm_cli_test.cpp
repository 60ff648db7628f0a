// The farm-facing command line end to end: frame ranges and frame-numbered
// names, frame-keyed scenes, tiles and merge, chained steps, batch files.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "core/image/io/image_io.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/vdb_fixtures.hpp"

using namespace weft::test;
namespace fs = std::filesystem;

namespace {

std::string meta(const weft::Metadata& md, const std::string& key) {
    for (const auto& [k, v] : md)
        if (k == key) return v;
    return "";
}

bool samePixels(const weft::Image& a, const weft::Image& b) {
    return a.width() == b.width() && a.height() == b.height() && a.channelNames() == b.channelNames() &&
           std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(float)) == 0;
}

weft::Image load(const fs::path& p, weft::Metadata* md = nullptr) { return weft::readImage(p.string(), md); }

std::string s(const fs::path& p) { return p.string(); }

TEST(FarmFrames, RendersASequenceWithPaddedNamesInEveryOutput) {
    TempDir dir;
    writeProceduralVdb(dir / "seq.0001.vdb", "sphere", 16);
    writeProceduralVdb(dir / "seq.0002.vdb", "cloud", 16);
    const auto r = runWeft("render " + s(dir / "seq.#.vdb") + " --frames 1-2 --res 20x16 -o " + s(dir / "out.#.exr") +
                           " --preview " + s(dir / "p.@@.png") + " --stats " + s(dir / "s.@.json"));
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char* f : {"out.0001.exr", "out.0002.exr", "p.01.png", "p.02.png", "s.1.json", "s.2.json"})
        EXPECT_TRUE(fs::exists(dir / f)) << f;
    // Each frame is exactly the single render of its own file.
    ASSERT_EQ(runWeft("render " + s(dir / "seq.0002.vdb") + " --res 20x16 -o " + s(dir / "single.exr")).status, 0);
    weft::Metadata md;
    const weft::Image two = load(dir / "out.0002.exr", &md);
    EXPECT_TRUE(samePixels(two, load(dir / "single.exr")));
    EXPECT_FALSE(samePixels(two, load(dir / "out.0001.exr")));
    EXPECT_EQ(meta(md, "weft:frame"), "2");
    EXPECT_EQ(meta(md, "weft:input"), s(dir / "seq.0002.vdb"));
}

TEST(FarmFrames, SeveralFramesNeedAWildcardInEachOutputName) {
    TempDir dir;
    auto r = runWeft("render builtin:sphere --frames 1-2 --res 8x8 -o " + s(dir / "same.exr"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("has no frame number"), std::string::npos) << r.output;
    r = runWeft("render builtin:sphere --frames 1-2 --res 8x8 -o " + s(dir / "o.#.exr") + " --stats " + s(dir / "s.json"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("stats '"), std::string::npos) << r.output;
    r = runWeft("render builtin:sphere --frames 3-1x0 --res 8x8 -o " + s(dir / "o.#.exr"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("bad frame range '3-1x0'"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(FarmFrames, AFrameWithBadInputFailsAndTheOthersGoOn) {
    TempDir dir;
    writeProceduralVdb(dir / "seq.0001.vdb", "sphere", 16);
    writeProceduralVdb(dir / "seq.0003.vdb", "sphere", 16);
    writeText(dir / "seq.0002.vdb", "not a vdb");
    const auto r = runWeft("render " + s(dir / "seq.#.vdb") + " --frames 1-4 --res 8x8 -o " + s(dir / "o.#.exr"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("frame 2: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("frame 4: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("2 of 4 renders failed"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(dir / "o.0001.exr"));
    EXPECT_TRUE(fs::exists(dir / "o.0003.exr"));
    EXPECT_FALSE(fs::exists(dir / "o.0002.exr"));
    EXPECT_FALSE(fs::exists(dir / "o.0004.exr"));
}

std::string sceneWithCamera(const std::string& camera, const std::string& file = "") {
    const std::string volume = file.empty() ? R"({"procedural": "sphere", "resolution": 16})" : R"({"file": ")" + file + R"("})";
    return R"({"volumes": [)" + volume + R"(], "camera": )" + camera + R"(, "render": {"resolution": [24, 16]}})";
}

TEST(FarmFrames, KeyedCameraInterpolatesLinearlyBetweenKeys) {
    TempDir dir;
    writeText(dir / "keyed.json", sceneWithCamera(R"({"up": [0, 1, 0], "keys": [
        {"frame": 10, "eye": [0, 0, 4], "target": [0, 0, 0], "fov": 30},
        {"frame": 14, "eye": [2, 1, 4], "target": [0, 0, 0], "fov": 50}]})"));
    writeText(dir / "mid.json", sceneWithCamera(R"({"eye": [1, 0.5, 4], "target": [0, 0, 0], "fov": 40})"));
    writeText(dir / "first.json", sceneWithCamera(R"({"eye": [0, 0, 4], "target": [0, 0, 0], "fov": 30})"));
    ASSERT_EQ(runWeft("render " + s(dir / "keyed.json") + " --frames 8,12,16 -o " + s(dir / "k.@@.exr")).status, 0);
    ASSERT_EQ(runWeft("render " + s(dir / "mid.json") + " -o " + s(dir / "mid.exr")).status, 0);
    ASSERT_EQ(runWeft("render " + s(dir / "first.json") + " -o " + s(dir / "first.exr")).status, 0);
    ASSERT_EQ(runWeft("render " + s(dir / "keyed.json") + " -o " + s(dir / "nokey.exr")).status, 0);
    EXPECT_TRUE(samePixels(load(dir / "k.12.exr"), load(dir / "mid.exr")));
    EXPECT_TRUE(samePixels(load(dir / "k.08.exr"), load(dir / "first.exr")));  // held before the first key
    EXPECT_TRUE(samePixels(load(dir / "nokey.exr"), load(dir / "first.exr")));  // no frame: the first key
    EXPECT_FALSE(samePixels(load(dir / "k.16.exr"), load(dir / "mid.exr")));
}

TEST(FarmFrames, SceneVolumeFileIsFrameNumbered) {
    TempDir dir;
    writeProceduralVdb(dir / "v.0005.vdb", "sphere", 16);
    writeText(dir / "seq.json", sceneWithCamera(R"({"eye": [0, 0, 4], "target": [0, 0, 0]})", "v.#.vdb"));
    ASSERT_EQ(runWeft("render " + s(dir / "seq.json") + " --frames 5 -o " + s(dir / "o.#.exr")).status, 0);
    const auto r = runWeft("render " + s(dir / "seq.json") + " --frames 6 -o " + s(dir / "o.#.exr"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("v.0006.vdb"), std::string::npos) << r.output;
    writeText(dir / "bad.json", sceneWithCamera(R"({"keys": [{"frame": 2, "eye": [0, 0, 4]}, {"frame": 1, "eye": [0, 0, 3]}]})"));
    const auto bad = runWeft("render " + s(dir / "bad.json") + " -o " + s(dir / "b.exr"));
    EXPECT_NE(bad.output.find("camera key frames must increase"), std::string::npos) << bad.output;
}

// Tiles rendered separately and merged equal the single render bit for bit.
void expectTilesMergeToSingle(const std::string& technique, const std::string& res, int count) {
    TempDir dir;
    writeText(dir / "cloud.json", R"({"volumes": [{"procedural": "cloud", "resolution": 32}]})");
    const std::string common = "render " + s(dir / "cloud.json") + " --technique " + technique + " --res " + res +
                               " --spp 2 --seed 5 --set jitter=true --threads 2 ";
    ASSERT_EQ(runWeft(common + "-o " + s(dir / "full.exr")).status, 0);
    std::string tiles;
    for (int i = count; i >= 1; --i) {  // any order
        const fs::path t = dir / ("t" + std::to_string(i) + ".exr");
        const auto r = runWeft(common + "--tile " + std::to_string(i) + "/" + std::to_string(count) + " -o " + s(t));
        ASSERT_EQ(r.status, 0) << r.output;
        tiles += s(t) + " ";
    }
    const auto r = runWeft("merge " + tiles + "-o " + s(dir / "merged.exr"));
    ASSERT_EQ(r.status, 0) << r.output;
    weft::Metadata tileMd, mergedMd, fullMd;
    const weft::Image tile = load(dir / "t1.exr", &tileMd);
    EXPECT_LT(tile.height(), load(dir / "full.exr").height());
    EXPECT_EQ(meta(tileMd, "weft:tile"), "1/" + std::to_string(count));
    EXPECT_FALSE(meta(tileMd, "weft:tile:data_window").empty());
    EXPECT_TRUE(samePixels(load(dir / "merged.exr", &mergedMd), load(dir / "full.exr", &fullMd))) << technique << " " << count;
    EXPECT_EQ(meta(mergedMd, "weft:counter:rays.camera"), meta(fullMd, "weft:counter:rays.camera"));
    EXPECT_EQ(meta(mergedMd, "weft:complete"), "1");
}

TEST(FarmTiles, MergedTilesEqualTheSingleRenderRaymarch) {
    for (int count : {2, 3, 7}) expectTilesMergeToSingle("volume.raymarch", "37x29", count);
}

TEST(FarmTiles, MergedTilesEqualTheSingleRenderSingleScatter) {
    expectTilesMergeToSingle("volume.singlescatter", "21x13", 4);
}

TEST(FarmTiles, MergeRefusesIncompleteDuplicateAndMismatchedSets) {
    TempDir dir;
    const std::string common = "render builtin:sphere --res 16x10 ";
    for (int i = 1; i <= 3; ++i)
        ASSERT_EQ(runWeft(common + "--tile " + std::to_string(i) + "/3 -o " + s(dir / ("t" + std::to_string(i) + ".exr"))).status, 0);
    ASSERT_EQ(runWeft(common + "--seed 9 --tile 2/3 -o " + s(dir / "other.exr")).status, 0);
    ASSERT_EQ(runWeft(common + "-o " + s(dir / "full.exr")).status, 0);
    const std::string out = " -o " + s(dir / "m.exr");
    const std::pair<std::string, std::string> cases[] = {
        {s(dir / "t1.exr") + " " + s(dir / "t3.exr"), "missing tile(s) 2 of 3"},
        {s(dir / "t1.exr") + " " + s(dir / "t2.exr") + " " + s(dir / "t2.exr") + " " + s(dir / "t3.exr"), "tile 2/3 given twice"},
        {s(dir / "t1.exr") + " " + s(dir / "other.exr") + " " + s(dir / "t3.exr"), "different renders (weft:seed"},
        {s(dir / "t1.exr") + " " + s(dir / "full.exr"), "is not a tile"},
        {s(dir / "t1.exr") + " " + s(dir / "nope.exr"), "no such file"},
    };
    for (const auto& [args, expected] : cases) {
        const auto r = runWeft("merge " + args + out);
        EXPECT_EQ(r.status, 1) << args;
        EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_FALSE(fs::exists(dir / "m.exr"));
    }
}

TEST(FarmChain, StepsConsumeThePreviousResultInOrder) {
    TempDir dir;
    const std::string render = "render builtin:sphere --res 16x12 --seed 2 ";
    ASSERT_EQ(runWeft(render + "-o " + s(dir / "plain.exr")).status, 0);
    const auto r = runWeft(render + "exposure 1 write " + s(dir / "x1.exr") + " exposure 1 preview " + s(dir / "x2.png") +
                           " write " + s(dir / "x2.exr"));
    ASSERT_EQ(r.status, 0) << r.output;
    weft::Metadata md;
    const weft::Image plain = load(dir / "plain.exr"), x1 = load(dir / "x1.exr", &md), x2 = load(dir / "x2.exr");
    EXPECT_TRUE(fs::exists(dir / "x2.png"));
    EXPECT_EQ(meta(md, "weft:chain"), "exposure 1");
    EXPECT_EQ(meta(md, "weft:complete"), "1");
    double rgbSum = 0;
    for (int y = 0; y < plain.height(); ++y)
        for (int x = 0; x < plain.width(); ++x) {
            for (int c = 0; c < 3; ++c) {
                EXPECT_EQ(x1.at(x, y, c), 2.0f * plain.at(x, y, c));
                EXPECT_EQ(x2.at(x, y, c), 4.0f * plain.at(x, y, c));
                rgbSum += plain.at(x, y, c);
            }
            EXPECT_EQ(x2.at(x, y, 3), plain.at(x, y, 3));  // alpha untouched
        }
    EXPECT_GT(rgbSum, 0.0);
}

TEST(FarmChain, StepsWithoutAnImageOrAnOutputAreErrors) {
    TempDir dir;
    auto r = runWeft("exposure 1 write " + s(dir / "x.exr"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("'exposure' needs an image"), std::string::npos) << r.output;
    r = runWeft("render builtin:sphere --res 8x8 exposure 1");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("nothing written"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(FarmChain, StepsRunOnEveryFrameWithFrameNumberedNames) {
    TempDir dir;
    writeProceduralVdb(dir / "seq.0001.vdb", "sphere", 16);
    writeProceduralVdb(dir / "seq.0002.vdb", "cloud", 16);
    const std::string render = "render " + s(dir / "seq.#.vdb") + " --frames 1-2 --res 16x12 ";
    auto r = runWeft(render + "exposure 1 write " + s(dir / "one.exr"));  // both frames would write one file
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("'write': '" + s(dir / "one.exr") + "' has no frame number"), std::string::npos) << r.output;
    r = runWeft(render + "exposure 1 preview " + s(dir / "p.#.png") + " write " + s(dir / "x.#.exr"));
    ASSERT_EQ(r.status, 0) << r.output;
    ASSERT_EQ(runWeft(render + "-o " + s(dir / "plain.#.exr")).status, 0);
    for (const char* f : {"0001", "0002"}) {
        weft::Metadata md;
        const weft::Image x = load(dir / ("x." + std::string(f) + ".exr"), &md), plain = load(dir / ("plain." + std::string(f) + ".exr"));
        EXPECT_TRUE(fs::exists(dir / ("p." + std::string(f) + ".png")));
        EXPECT_EQ(meta(md, "weft:frame"), std::string(1, f[3]));
        EXPECT_EQ(meta(md, "weft:chain"), "exposure 1");
        for (int y = 0; y < x.height(); ++y)
            for (int px = 0; px < x.width(); ++px) EXPECT_EQ(x.at(px, y, 0), 2.0f * plain.at(px, y, 0));
    }
}

TEST(FarmChain, AtrousStepIsTheFilterCommand) {
    TempDir dir;
    const std::string render = "render builtin:cloud --res 24x16 --spp 2 --set jitter=true ";
    const std::string sets = "--set levels=3 --set sigma_color=0.2 --set sigma_normal=0 --set sigma_position=0";
    ASSERT_EQ(runWeft(render + "-o " + s(dir / "noisy.exr")).status, 0);
    ASSERT_EQ(runWeft("filter atrous " + s(dir / "noisy.exr") + " -o " + s(dir / "filtered.exr") + " " + sets).status, 0);
    const auto r = runWeft(render + "atrous " + sets + " write " + s(dir / "chained.exr"));
    ASSERT_EQ(r.status, 0) << r.output;
    weft::Metadata md;
    const weft::Image chained = load(dir / "chained.exr", &md);
    EXPECT_TRUE(samePixels(chained, load(dir / "filtered.exr")));
    EXPECT_FALSE(samePixels(chained, load(dir / "noisy.exr")));
    EXPECT_EQ(meta(md, "weft:filter:atrous:levels"), "3");
    EXPECT_EQ(meta(md, "weft:chain"), "atrous levels=3 sigma_color=0.2 sigma_normal=0 sigma_position=0");
}

TEST(FarmChain, ColorconvertGoesThroughOpenColorIO) {
    TempDir dir;
    const std::string render = "render builtin:cloud --res 16x12 --seed 4 ";
    ASSERT_EQ(runWeft(render + "-o " + s(dir / "lin.exr")).status, 0);
    auto r = runWeft(render + "colorconvert lin_rec709 acescg write " + s(dir / "ap1.exr") +
                     " colorconvert acescg lin_rec709 write " + s(dir / "back.exr"));
    ASSERT_EQ(r.status, 0) << r.output;
    ASSERT_EQ(runWeft(render + "colorconvert lin_rec709 srgb_display write " + s(dir / "srgb.exr")).status, 0);
    const weft::Image lin = load(dir / "lin.exr"), ap1 = load(dir / "ap1.exr"), back = load(dir / "back.exr"), srgb = load(dir / "srgb.exr");
    int partlyCovered = 0;
    for (int y = 0; y < lin.height(); ++y)
        for (int x = 0; x < lin.width(); ++x) {
            const float a = lin.at(x, y, 3), R = lin.at(x, y, 0), G = lin.at(x, y, 1), B = lin.at(x, y, 2);
            EXPECT_NEAR(ap1.at(x, y, 0), 0.6130974f * R + 0.3395231f * G + 0.0473795f * B, 1e-5f);  // a matrix: premultiplication commutes
            for (int c = 0; c < 4; ++c) EXPECT_NEAR(back.at(x, y, c), lin.at(x, y, c), 1e-5f);
            EXPECT_EQ(srgb.at(x, y, 3), a);
            if (a > 0.01f && a < 0.99f) {  // the curve applies to the un-premultiplied colour
                ++partlyCovered;
                const float v = R / a, encoded = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
                EXPECT_NEAR(srgb.at(x, y, 0), encoded * a, 1e-4f);
            }
        }
    EXPECT_GT(partlyCovered, 0);
    r = runWeft(render + "colorconvert lin_rec709 rec2020 write " + s(dir / "x.exr"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("unknown colour space 'rec2020'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("acescg"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "x.exr"));
}

TEST(FarmBatch, RendersEveryJobAndChecksAllJobsFirst) {
    TempDir dir;
    writeText(dir / "jobs.json", R"({"jobs": [
      {"input": "builtin:sphere", "output": ")" + s(dir / "a.#.exr") + R"(", "frames": "1-2", "res": "16x12", "set": {"step": 0.25}},
      {"input": "builtin:cloud", "output": ")" + s(dir / "b.exr") + R"(", "res": "16x12", "tile": "2/2", "seed": 3}]})");
    const auto r = runWeft("batch " + s(dir / "jobs.json"));
    ASSERT_EQ(r.status, 0) << r.output;
    ASSERT_EQ(runWeft("render builtin:sphere --res 16x12 --set step=0.25 -o " + s(dir / "ref.exr")).status, 0);
    EXPECT_TRUE(samePixels(load(dir / "a.0002.exr"), load(dir / "ref.exr")));
    weft::Metadata md;
    EXPECT_EQ(load(dir / "b.exr", &md).height(), 6);
    EXPECT_EQ(meta(md, "weft:tile"), "2/2");
    EXPECT_EQ(meta(md, "weft:seed"), "3");

    writeText(dir / "bad.json", R"({"jobs": [
      {"input": "builtin:sphere", "output": ")" + s(dir / "never.exr") + R"(", "res": "8x8"},
      {"input": "builtin:sphere", "output": ")" + s(dir / "never2.exr") + R"(", "colour": "red"}]})");
    const auto bad = runWeft("batch " + s(dir / "bad.json"));
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.output.find("job 2: unknown key 'colour'"), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(dir / "never.exr"));  // nothing renders before every job is checked
}

}  // namespace
