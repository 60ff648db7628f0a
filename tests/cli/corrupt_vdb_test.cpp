// A corrupt .vdb gives the same outcome on every run and any thread count.
// Single bytes changed in the committed smoke (each 0x00 -> 0xDA, in the
// per-leaf sizes OpenVDB keeps for its own delayed loading) made OpenVDB's
// delayed load read a raw chunk past its buffer: a crash in some runs, a
// refusal ("does not fit in memory") in others. weft reads every leaf where
// its own walk of the file found it, so these render the clean file's image.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "tests/support/test_support.hpp"

using namespace weft::test;

namespace {

TEST(CorruptVdb, OneChangedByteGivesOneOutcomeOnEveryRunAndThreadCount) {
    const std::string source = std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb", good = readBytes(source);
    ASSERT_GT(good.size(), 1000u);
    TempDir dir;
    const std::string args = " --technique volume.adaptive3d --res 32x32 -o ";
    ASSERT_EQ(runWeft("render " + source + args + (dir / "clean.exr").string()).status, 0);
    for (const std::size_t offset : {747u, 767u, 785u, 791u, 841u}) {
        ASSERT_EQ(good[offset], '\0') << offset;
        std::string bad = good;
        bad[offset] = char(0xDA);
        const auto path = dir / ("bad" + std::to_string(offset) + ".vdb");
        writeText(path, bad);
        std::set<std::string> outcomes;
        for (const char* threads : {"1", "2", "2", "2", "2", "2"}) {
            const CommandResult r = runWeft("render " + path.string() + args + (dir / "out.exr").string() + " --threads " + threads);
            outcomes.insert(std::to_string(r.status) + " " + r.output);
        }
        ASSERT_EQ(outcomes.size(), 1u) << offset << ": " << *outcomes.begin() << " / " << *outcomes.rbegin();
        EXPECT_EQ(*outcomes.begin(), "0 ") << offset;
        const CommandResult same = runWeft("diff " + (dir / "out.exr").string() + " " + (dir / "clean.exr").string() + " --fail 0");
        EXPECT_EQ(same.status, 0) << offset << ": " << same.output;
    }
}

}  // namespace
