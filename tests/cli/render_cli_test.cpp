// The weft host end to end: renders, determinism across thread counts,
// metadata, stats JSON, help, plugin listing, external plugins and diff.
#include <gtest/gtest.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "core/image/io/image_io.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/vdb_fixtures.hpp"

using namespace weft::test;

namespace {

std::string metaValue(const weft::Metadata& md, const std::string& key) {
    for (const auto& [k, v] : md)
        if (k == key) return v;
    return "";
}

TEST(RenderCli, SameSeedSameBytesOnOneAndTwoThreads) {
    TempDir dir;
    const std::string common = "render builtin:cloud --res 64x48 --spp 2 --set jitter=true --seed 7 ";
    ASSERT_EQ(runWeft(common + "--threads 1 -o " + (dir / "t1.exr").string()).status, 0);
    ASSERT_EQ(runWeft(common + "--threads 2 -o " + (dir / "t2.exr").string()).status, 0);
    const std::string a = readBytes(dir / "t1.exr"), b = readBytes(dir / "t2.exr");
    ASSERT_GT(a.size(), 1000u);
    EXPECT_TRUE(a == b) << "EXR bytes differ between 1 and 2 threads";
    // A different seed must change the jittered image.
    ASSERT_EQ(runWeft(common.substr(0, common.find("--seed")) + "--seed 8 -o " + (dir / "s8.exr").string()).status, 0);
    EXPECT_NE(readBytes(dir / "s8.exr"), a);
}

TEST(RenderCli, WritesMetadataStatsAndPreview) {
    TempDir dir;
    const auto r = runWeft("render builtin:sphere --res 32x32 --set step=0.25 --seed 3 -o " + (dir / "o.exr").string() +
                           " --preview " + (dir / "o.png").string() + " --stats " + (dir / "s.json").string() + " -v");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("volume.samples"), std::string::npos);  // -v prints the counter table
    weft::Metadata md;
    const weft::Image img = weft::readImage((dir / "o.exr").string(), &md);
    EXPECT_EQ(img.width(), 32);
    EXPECT_EQ(img.channelNames(), (std::vector<std::string>{"R", "G", "B", "A"}));
    EXPECT_EQ(metaValue(md, "weft:technique"), "volume.raymarch");
    EXPECT_EQ(metaValue(md, "weft:param:step"), "0.25");
    EXPECT_EQ(metaValue(md, "weft:param:jitter"), "false");
    EXPECT_EQ(metaValue(md, "weft:seed"), "3");
    EXPECT_EQ(metaValue(md, "weft:complete"), "1");
    EXPECT_FALSE(metaValue(md, "weft:version").empty());
    const auto stats = nlohmann::json::parse(readBytes(dir / "s.json"));
    EXPECT_EQ(stats["counters"]["rays.camera"].get<long long>(), 32 * 32);
    EXPECT_EQ(std::to_string(stats["counters"]["volume.samples"].get<long long>()), metaValue(md, "weft:counter:volume.samples"));
    EXPECT_GT(stats["counters"]["volume.samples"].get<long long>(), 32 * 32);
    for (const char* phase : {"load", "setup", "render", "write"}) EXPECT_TRUE(stats["timings_ms"].contains(phase)) << phase;
    const weft::Image png = weft::readImage((dir / "o.png").string());
    EXPECT_EQ(png.channelCount(), 3);
    EXPECT_EQ(png.width(), 32);
}

// --compression and -d choose the EXR's encoding and say so in its
// metadata; a bad value is one line before anything renders, and no file.
TEST(RenderCli, CompressionAndPixelTypesAreChosenAndRecorded) {
    TempDir dir;
    const auto r = runWeft("render builtin:sphere --res 24x16 --compression piz -d half -d A=float -o " + (dir / "h.exr").string());
    ASSERT_EQ(r.status, 0) << r.output;
    weft::Metadata md;
    const weft::Image half = weft::readImage((dir / "h.exr").string(), &md);
    EXPECT_EQ(metaValue(md, "weft:compression"), "piz");
    EXPECT_EQ(metaValue(md, "weft:pixel_types"), "A float; R,G,B half");
    EXPECT_EQ(metaValue(md, "compression"), "piz");  // OpenEXR's own field, as OpenImageIO reads it
    ASSERT_EQ(runWeft("render builtin:sphere --res 24x16 -o " + (dir / "f.exr").string()).status, 0);
    md.clear();
    const weft::Image full = weft::readImage((dir / "f.exr").string(), &md);
    EXPECT_EQ(metaValue(md, "weft:pixel_types"), "float");
    EXPECT_FALSE(metaValue(md, "weft:compression").empty());
    for (std::size_t i = 0; i < full.data().size(); ++i)
        ASSERT_NEAR(half.data()[i], full.data()[i], std::abs(full.data()[i]) / 1024 + 1e-7) << i;
    const auto unmatched = runWeft("render builtin:sphere --res 8x8 -d Z=half -o " + (dir / "z.exr").string());
    EXPECT_EQ(unmatched.status, 0);
    EXPECT_NE(unmatched.output.find("-d 'Z=half' names no channel"), std::string::npos) << unmatched.output;
    for (const std::string bad : {"--compression zstd", "-d quarter", "-d =half"}) {
        const auto out = runWeft("render builtin:sphere --res 8x8 " + bad + " -o " + (dir / "bad.exr").string());
        EXPECT_NE(out.status, 0) << bad;
        EXPECT_EQ(std::count(out.output.begin(), out.output.end(), '\n'), 1) << bad << ": " << out.output;
        EXPECT_NE(out.output.find(bad.substr(bad.find(' ') + 1)), std::string::npos) << out.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "bad.exr")) << bad;
    }
}

TEST(RenderCli, BareVdbIsFramedAndRendered) {
    TempDir dir;
    writeProceduralVdb(dir / "sphere.vdb", "sphere", 16);
    const auto r = runWeft("render " + (dir / "sphere.vdb").string() + " --res 32x32 -o " + (dir / "v.exr").string());
    ASSERT_EQ(r.status, 0) << r.output;
    const weft::Image img = weft::readImage((dir / "v.exr").string());
    // Framed: the centre is covered, the corners are empty.
    EXPECT_GT(img.at(16, 16, 3), 0.2f);
    EXPECT_EQ(img.at(0, 0, 3), 0.0f);
}

TEST(RenderCli, ListPluginsAndHelpComeFromTheParameterTable) {
    const auto list = runWeft("--list-plugins");
    ASSERT_EQ(list.status, 0);
    EXPECT_NE(list.output.find("volume.raymarch"), std::string::npos);
    const auto help = runWeft("help volume.raymarch");
    ASSERT_EQ(help.status, 0);
    for (const char* s : {"step", "jitter", "ert", "skip_empty", "[1e-04, 64]", "default 0.5"})
        EXPECT_NE(help.output.find(s), std::string::npos) << s;
    const auto unknown = runWeft("help volume.nope");
    EXPECT_NE(unknown.status, 0);
    EXPECT_NE(unknown.output.find("unknown technique 'volume.nope'"), std::string::npos);
}

TEST(RenderCli, ExternalPluginOnPluginPath) {
    const std::string env = "WEFT_PLUGIN_PATH=" + std::string(WEFT_TEST_PLUGIN_DIR);
    const auto list = runWeft("--list-plugins", env);
    ASSERT_EQ(list.status, 0) << list.output;
    EXPECT_NE(list.output.find("example.gradient"), std::string::npos) << list.output;
    EXPECT_EQ(runWeft("--list-plugins").output.find("example.gradient"), std::string::npos);
    TempDir dir;
    const auto r = runWeft("render builtin:sphere --technique example.gradient --set gain=2 --res 16x4 -o " +
                           (dir / "g.exr").string(), env);
    ASSERT_EQ(r.status, 0) << r.output;
    const weft::Image img = weft::readImage((dir / "g.exr").string());
    EXPECT_NEAR(img.at(15, 0, 0), 2.0f * 15.5f / 16.0f, 1e-6);
    EXPECT_NEAR(img.at(0, 3, 1), 2.0f * 0.5f / 16.0f, 1e-6);
    const auto bad = runWeft("render builtin:sphere --technique example.gradient --set gain=11 --res 4x4 -o " +
                             (dir / "b.exr").string(), env);
    EXPECT_NE(bad.output.find("allowed [0, 10]"), std::string::npos) << bad.output;
}

TEST(RenderCli, PluginWithWrongAbiIsRefusedClearly) {
    TempDir dir;
    writeText(dir / "broken.weft.so", "not a shared library");
    const auto r = runWeft("--list-plugins", "WEFT_PLUGIN_PATH=" + dir.path().string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("plugin '" + (dir / "broken.weft.so").string() + "'"), std::string::npos) << r.output;
}

TEST(DiffCli, ReportsMetricsAndFailsAboveThreshold) {
    TempDir dir;
    const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
    ASSERT_EQ(runWeft("render builtin:sphere --res 32x32 --set step=1 -o " + a).status, 0);
    ASSERT_EQ(runWeft("render builtin:sphere --res 32x32 --set step=0.25 -o " + b).status, 0);
    const auto same = runWeft("diff " + a + " " + a + " --fail 0");
    EXPECT_EQ(same.status, 0) << same.output;
    EXPECT_NE(same.output.find("inf"), std::string::npos);  // PSNR of identical images
    const auto differ = runWeft("diff " + a + " " + b);
    EXPECT_EQ(differ.status, 0);
    for (const char* s : {"RMSE", "relMSE", "PSNR", "SSIM", "maxAbs", "all"}) EXPECT_NE(differ.output.find(s), std::string::npos);
    const auto fail = runWeft("diff " + a + " " + b + " --fail 0.0000001");
    EXPECT_EQ(fail.status, 2) << fail.output;
    const auto missing = runWeft("diff " + a + " " + (dir / "none.exr").string());
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.output.find("no such file"), std::string::npos);
}

// A cut or corrupt image is named in weft's words: one line, no library
// exception text ("OpenEXR", "Iex") and no raw bytes of the file.
TEST(DiffCli, CorruptImagesInOwnWords) {
    TempDir dir;
    const std::string good = (dir / "good.exr").string();
    ASSERT_EQ(runWeft("render builtin:sphere --res 32x32 -o " + good).status, 0);
    const std::string bytes = readBytes(good);
    writeText(dir / "cut.exr", bytes.substr(0, bytes.size() * 2 / 3));
    std::string junk = bytes.substr(0, 8);
    for (int i = 0; i < 4096; ++i) junk += char((i * 131 + 7) & 0xff);
    writeText(dir / "junk.exr", junk);
    writeText(dir / "text.exr", "not an image\n");
    for (const char* name : {"cut.exr", "junk.exr", "text.exr"}) {
        const auto r = runWeft("diff " + (dir / name).string() + " " + good);
        EXPECT_EQ(r.status, 1) << name << ": " << r.output;
        EXPECT_NE(r.output.find(std::string("image '") + (dir / name).string() + "': cannot be read: "), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("OpenEXR"), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    }
}

}  // namespace
