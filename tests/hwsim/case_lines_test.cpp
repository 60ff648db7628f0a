// The CASE line format: written and read back, the fields before the
// pipeline statistics still read alone (older recordings), malformed lines skipped.
#include <gtest/gtest.h>

#include "tests/hwsim/case_lines.hpp"

namespace weft::crosscheck {
namespace {

TEST(HwsimCaseLines, RoundTripWithStatistics) {
    Counts c;
    c.samplesPassed = 12, c.invocations = 34, c.fsInvocations = 48, c.clipIn = 4, c.clipOut = 3;
    c.markWritten(5, 6);
    const auto parsed = parseCaseLines("RENDERER x\n" + caseLine("some_case", c) + "\n");
    ASSERT_EQ(parsed.size(), 1u);
    const Counts& p = parsed.at("some_case");
    EXPECT_EQ(p.samplesPassed, 12);
    EXPECT_EQ(p.invocations, 34);
    EXPECT_EQ(p.written, 1);
    EXPECT_EQ(p.writtenHash, c.writtenHash);
    EXPECT_EQ(p.fsInvocations, 48);
    EXPECT_EQ(p.clipIn, 4);
    EXPECT_EQ(p.clipOut, 3);
}

TEST(HwsimCaseLines, OlderLinesLackOnlyTheStatistics) {
    const auto parsed = parseCaseLines(
        "CASE old samples=1 invocations=2 written=3 hash=4\n"
        "CASE torn samples=1 invocations=2 written=3 hash=4 fs_invocations=5\n"
        "CASE short samples=1 invocations=2\n"
        "SKIP other no GL_EXT_depth_bounds_test\n");
    ASSERT_EQ(parsed.size(), 1u);
    const Counts& p = parsed.at("old");
    EXPECT_EQ(p.samplesPassed, 1);
    EXPECT_EQ(p.writtenHash, 4u);
    EXPECT_EQ(p.fsInvocations, -1);
    EXPECT_EQ(p.clipIn, -1);
    EXPECT_EQ(p.clipOut, -1);
}

}  // namespace
}  // namespace weft::crosscheck
