// No output ever replaces what the user made: an output naming an input (by
// any spelling: a link, a hard link, the same path) is refused before a
// render, a merge or a filter starts; a device or FIFO is written into (text)
// or refused, never replaced by a file; a full disk leaves the previous file
// whole; a long legal name is not refused for its temporary's sake.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "tests/support/test_support.hpp"

using namespace weft::test;
namespace fs = std::filesystem;

namespace {

const std::string kSmoke = std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb";

// A scene of the committed smoke, rendered small; returns its path.
fs::path writeScene(const TempDir& dir) {
    fs::copy_file(kSmoke, dir / "smoke.vdb");
    const fs::path scene = dir / "scene.json";
    writeText(scene, R"({"volumes": [{"file": "smoke.vdb"}], "render": {"technique": "volume.raymarch", "resolution": [16, 16]}})");
    return scene;
}

void expectRefusedAndKept(const CommandResult& r, const fs::path& kept, const std::string& before, const std::string& words) {
    EXPECT_NE(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(words), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("weft-tmp"), std::string::npos) << r.output;
    EXPECT_EQ(readBytes(kept), before) << kept;
}

TEST(OutputSafety, StatsNamingTheSceneIsRefusedAndTheSceneKept) {
    TempDir dir;
    const fs::path scene = writeScene(dir);
    const std::string text = readBytes(scene);
    const CommandResult r = runWeft("render " + scene.string() + " -o " + (dir / "out.exr").string() + " --stats " + scene.string());
    expectRefusedAndKept(r, scene, text, "is the scene");
    EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

TEST(OutputSafety, OutputsNamingAVolumeByAnotherSpellingAreRefused) {
    TempDir dir;
    const fs::path scene = writeScene(dir);
    const std::string vdb = readBytes(dir / "smoke.vdb");
    fs::create_symlink(dir / "smoke.vdb", dir / "link.json");
    fs::create_hard_link(dir / "smoke.vdb", dir / "hard.exr");
    const std::string base = "render " + scene.string() + " ";
    expectRefusedAndKept(runWeft(base + "-o " + (dir / "x.exr").string() + " --stats " + (dir / "link.json").string()),
                         dir / "smoke.vdb", vdb, "is the volume");
    expectRefusedAndKept(runWeft(base + "-o " + (dir / "hard.exr").string()), dir / "smoke.vdb", vdb, "is the volume");
    expectRefusedAndKept(runWeft("render " + (dir / "smoke.vdb").string() + " --res 8x8 -o " + (dir / "y.exr").string() +
                                 " --stats " + (dir / "./smoke.vdb").string()),
                         dir / "smoke.vdb", vdb, "is the volume");
    EXPECT_TRUE(fs::is_symlink(dir / "link.json"));
    EXPECT_FALSE(fs::exists(dir / "x.exr"));
}

TEST(OutputSafety, MergeAndFilterDoNotReplaceTheirInputs) {
    TempDir dir;
    const std::string t = (dir / "t").string();
    for (int i = 1; i <= 2; ++i)
        ASSERT_EQ(runWeft("render builtin:sphere --res 8x8 --tile " + std::to_string(i) + "/2 -o " + t + std::to_string(i) + ".exr").status, 0);
    const std::string tile1 = readBytes(t + "1.exr");
    expectRefusedAndKept(runWeft("merge " + t + "1.exr " + t + "2.exr -o " + t + "1.exr"), t + "1.exr", tile1, "is the image");
    ASSERT_EQ(runWeft("merge " + t + "1.exr " + t + "2.exr -o " + t + "m.exr").status, 0);
    const std::string merged = readBytes(t + "m.exr");
    expectRefusedAndKept(runWeft("filter atrous " + t + "m.exr -o " + t + "m.exr"), t + "m.exr", merged, "is the image");
}

TEST(OutputSafety, AFullDiskLeavesThePreviousVdbWhole) {
    TempDir dir;
    std::string bytes(16 * 16 * 16, '\0');
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = char(i * 7 % 251);
    writeText(dir / "in.raw", bytes);
    const std::string out = (dir / "out.vdb").string(), args = "convert " + (dir / "in.raw").string() + " --dims 16,16,16 --type u8 -o " + out;
    ASSERT_EQ(runWeft(args).status, 0);
    const std::string before = readBytes(out);
    ASSERT_GT(before.size(), 4096u);
    // A file size limit of 2 KiB makes every write past it fail (EFBIG), as a full disk would.
    const CommandResult r = runWeft(args, "trap '' XFSZ; ulimit -f 4;");
    EXPECT_NE(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("cannot write '" + out + "'"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("active voxels"), std::string::npos) << r.output;  // no success line
    EXPECT_EQ(readBytes(out), before);
    for (const auto& e : fs::directory_iterator(dir.path())) EXPECT_EQ(e.path().string().find("weft-tmp"), std::string::npos) << e.path();
}

TEST(OutputSafety, StatsGoIntoACharacterDeviceAndAFifoIsNeverReplaced) {
    TempDir dir;
    fs::create_symlink("/dev/null", dir / "null.json");
    const std::string base = "render builtin:sphere --res 8x8 ";
    const CommandResult ok = runWeft(base + "--stats " + (dir / "null.json").string());
    EXPECT_EQ(ok.status, 0) << ok.output;
    EXPECT_TRUE(fs::is_symlink(dir / "null.json"));
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
    const CommandResult out = runWeft(base + "--stats /dev/stdout");
    EXPECT_EQ(out.status, 0) << out.output;
    EXPECT_NE(out.output.find("\"counters\""), std::string::npos) << out.output;

    ASSERT_EQ(mkfifo((dir / "pipe.exr").c_str(), 0644), 0);
    ASSERT_EQ(mkfifo((dir / "pipe.json").c_str(), 0644), 0);
    const CommandResult image = runWeft(base + "-o " + (dir / "pipe.exr").string());
    EXPECT_NE(image.status, 0);
    EXPECT_NE(image.output.find("is a device, FIFO or socket"), std::string::npos) << image.output;
    // Refused before the render: no other output of the run is written.
    const CommandResult unread = runWeft(base + "--stats " + (dir / "pipe.json").string() + " -o " + (dir / "x.exr").string());
    EXPECT_NE(unread.status, 0);
    EXPECT_NE(unread.output.find("a FIFO that nobody reads"), std::string::npos) << unread.output;
    EXPECT_FALSE(fs::exists(dir / "x.exr"));
    EXPECT_TRUE(fs::is_fifo(dir / "pipe.exr"));
    EXPECT_TRUE(fs::is_fifo(dir / "pipe.json"));
}

TEST(OutputSafety, AnOutputThroughALinkReplacesWhatTheLinkNamesAndKeepsTheLink) {
    TempDir dir;
    writeText(dir / "old.json", "old stats");
    fs::create_symlink("old.json", dir / "link.json");
    const CommandResult r = runWeft("render builtin:sphere --res 8x8 --stats " + (dir / "link.json").string());
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(fs::is_symlink(dir / "link.json"));
    EXPECT_NE(readBytes(dir / "old.json").find("\"counters\""), std::string::npos);
}

TEST(OutputSafety, ALegalLongNameRendersAndAnIllegalOneFailsBeforeTheRender) {
    TempDir dir;
    const std::string longest = std::string(251, 'a') + ".exr";  // 255 bytes, NAME_MAX
    const CommandResult ok = runWeft("render builtin:sphere --res 8x8 -o " + (dir / longest).string());
    EXPECT_EQ(ok.status, 0) << ok.output;
    EXPECT_TRUE(fs::exists(dir / longest));
    const std::string tooLong = std::string(252, 'a') + ".exr";
    const CommandResult bad = runWeft("render builtin:sphere --res 8x8 -o " + (dir / tooLong).string() + " --stats " +
                                      (dir / "s.json").string());
    EXPECT_NE(bad.status, 0);
    EXPECT_NE(bad.output.find("its file name is 256 bytes"), std::string::npos) << bad.output;
    EXPECT_EQ(bad.output.find("weft-tmp"), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(dir / "s.json"));
}

}  // namespace
