// Scenes load in time and memory linear in what they name: a file named by
// many volumes is read once (its tree shared, counted once against
// --max-memory), and positions in a large scene file are found in one pass.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "tests/support/test_support.hpp"

using namespace weft::test;
namespace fs = std::filesystem;

namespace {

TEST(SceneLoad, AFileNamedByManyVolumesCountsOnceAgainstTheMemoryLimit) {
    TempDir dir;
    fs::copy_file(std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb", dir / "smoke.vdb");
    std::string scene = "{\"volumes\": [";
    for (int i = 0; i < 300; ++i) scene += std::string(i ? ", " : "") + "{\"file\": \"smoke.vdb\", \"translate\": [" + std::to_string(i) + ", 0, 0]}";
    writeText(dir / "many.json", scene + "]}\n");
    // 300 copies of the grid would need over 0.1 GiB; one is a few MB.
    const CommandResult r = runWeft("render " + (dir / "many.json").string() + " --res 16x16 --max-memory 0.05 -o " +
                                    (dir / "out.exr").string());
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "out.exr"));
}

TEST(SceneLoad, ThousandsOfLightsAndNumbersLoadAndErrorsKeepTheirPositions) {
    TempDir dir;
    std::string scene = "{\"volumes\": [{\"procedural\": \"sphere\", \"resolution\": 8}],\n \"lights\": [";
    for (int i = 0; i < 5000; ++i) scene += std::string(i ? ",\n" : "") + "{\"type\": \"directional\", \"direction\": [0, -1, 0], \"intensity\": 0.0001}";
    writeText(dir / "lights.json", scene + "],\n \"render\": {\"technique\": \"volume.singlescatter\"}}\n");
    const CommandResult ok = runWeft("render " + (dir / "lights.json").string() + " --res 8x8 -o " + (dir / "out.exr").string());
    EXPECT_EQ(ok.status, 0) << ok.output;
    // The last light's mistake is reported at its own line and column.
    writeText(dir / "bad.json", scene + ",\n{\"type\": \"directional\", \"intensity\": -1}]}\n");
    const CommandResult bad = runWeft("render " + (dir / "bad.json").string() + " --res 8x8 -o " + (dir / "bad.exr").string());
    EXPECT_NE(bad.status, 0);
    EXPECT_NE(bad.output.find("bad.json:5002:"), std::string::npos) << bad.output;
}

// Every input is checked as scene files are: a FIFO named as a batch file or a
// regression rule would block the read forever.
TEST(SceneLoad, FifosAsBatchOrRuleAreRefusedAtOnce) {
    TempDir dir;
    ASSERT_EQ(mkfifo((dir / "pipe").c_str(), 0600), 0);
    const CommandResult batch = runWeft("batch " + (dir / "pipe").string());
    EXPECT_NE(batch.status, 0);
    EXPECT_NE(batch.output.find("batch '" + (dir / "pipe").string() + "': is a FIFO"), std::string::npos) << batch.output;
    ASSERT_EQ(runWeft("render builtin:sphere --res 8x8 -o " + (dir / "a.exr").string()).status, 0);
    const CommandResult rule = runWeft("diff " + (dir / "a.exr").string() + " " + (dir / "a.exr").string() + " --rule " + (dir / "pipe").string());
    EXPECT_NE(rule.status, 0);
    EXPECT_NE(rule.output.find("is a FIFO"), std::string::npos) << rule.output;
    // A volume is no image: OpenImageIO's OpenVDB reader aborted on one OpenVDB asserts on.
    const std::string vdb = std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb";
    const CommandResult notImage = runWeft("diff " + vdb + " " + vdb);
    EXPECT_EQ(notImage.status, 1) << notImage.output;
    EXPECT_NE(notImage.output.find("not an image file weft reads"), std::string::npos) << notImage.output;
}

}  // namespace
