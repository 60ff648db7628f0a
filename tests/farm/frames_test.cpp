// Frame ranges, frame-numbered names and tile bands (core/base/options/frames.hpp).
#include "core/base/options/frames.hpp"

#include <gtest/gtest.h>

#include "core/base/error.hpp"

using weft::expandFrameName;
using weft::parseFrameRange;

namespace {

using V = std::vector<int>;

// The error must be one line and name the text it rejects.
void expectRangeError(const std::string& text) {
    try {
        parseFrameRange(text);
        ADD_FAILURE() << "'" << text << "' was accepted";
    } catch (const weft::Error& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        EXPECT_NE(msg.find("'" + text + "'"), std::string::npos) << msg;
    }
}

TEST(FrameRange, SpansStepsListsAndSingleFrames) {
    EXPECT_EQ(parseFrameRange("7"), V({7}));
    EXPECT_EQ(parseFrameRange("1001-1004"), V({1001, 1002, 1003, 1004}));
    EXPECT_EQ(parseFrameRange("1001-1010x3"), V({1001, 1004, 1007, 1010}));
    EXPECT_EQ(parseFrameRange("1001-1008x3"), V({1001, 1004, 1007}));  // the end need not be on the step
    EXPECT_EQ(parseFrameRange("1,3,5-9"), V({1, 3, 5, 6, 7, 8, 9}));
    EXPECT_EQ(parseFrameRange("1-100x2").size(), 50u);
}

TEST(FrameRange, NegativeFramesAndCountingDown) {
    EXPECT_EQ(parseFrameRange("-5--1"), V({-5, -4, -3, -2, -1}));
    EXPECT_EQ(parseFrameRange("-2-2"), V({-2, -1, 0, 1, 2}));
    EXPECT_EQ(parseFrameRange("-3"), V({-3}));
    EXPECT_EQ(parseFrameRange("5-1x2"), V({5, 3, 1}));
    EXPECT_EQ(parseFrameRange("-1--7x3"), V({-1, -4, -7}));
}

TEST(FrameRange, BadRangesAreOneLineErrorsNamingTheText) {
    for (const char* bad : {"", "a", "1-", "1-5x", "1-5x0", "1-5x-2", "1,,2", ",1", "1,", "1-5y2", "1--", "1 -5", "1.5",
                            "1-3,2", "99999999999", "0-2000000"})
        expectRangeError(bad);
}

TEST(FrameNames, HashIsFourDigitsAtEachAndAtIsOne) {
    EXPECT_EQ(expandFrameName("out.#.exr", 42), "out.0042.exr");
    EXPECT_EQ(expandFrameName("out.@.exr", 42), "out.42.exr");
    EXPECT_EQ(expandFrameName("out.@@@.exr", 7), "out.007.exr");
    EXPECT_EQ(expandFrameName("out.##.exr", 1001), "out.00001001.exr");
    EXPECT_EQ(expandFrameName("out.#@.exr", 3), "out.00003.exr");
    EXPECT_EQ(expandFrameName("out.####.exr", 1), "out.0000000000000001.exr");
    EXPECT_EQ(expandFrameName("out.%04d.exr", 12), "out.0012.exr");
    EXPECT_EQ(expandFrameName("out.%d.exr", 12), "out.12.exr");
    EXPECT_EQ(expandFrameName("out.#.exr", 123456), "out.123456.exr");  // wider than the padding
}

TEST(FrameNames, NegativeFramesCountTheSignInTheWidth) {
    EXPECT_EQ(expandFrameName("out.#.exr", -5), "out.-005.exr");
    EXPECT_EQ(expandFrameName("out.@.exr", -5), "out.-5.exr");
    EXPECT_EQ(expandFrameName("out.@@@@@.exr", -12), "out.-0012.exr");
}

TEST(FrameNames, OnlyTheFirstWildcardAndNoneMeansUnchanged) {
    EXPECT_EQ(expandFrameName("a/#/b.#.exr", 1), "a/0001/b.#.exr");
    EXPECT_EQ(expandFrameName("plain.exr", 5), "plain.exr");
    EXPECT_FALSE(weft::hasFrameWildcard("plain.exr"));
    EXPECT_FALSE(weft::hasFrameWildcard("100%.exr"));
    EXPECT_TRUE(weft::hasFrameWildcard("f.@@.exr"));
    EXPECT_TRUE(weft::hasFrameWildcard("f.%03d.exr"));
}

TEST(TileRows, BandsCoverTheImageOnceForCountsThatDoNotDivideIt) {
    for (int height : {1, 7, 48, 61})
        for (int count = 1; count <= std::min(height, 9); ++count) {
            int next = 0;
            for (int i = 1; i <= count; ++i) {
                const weft::RowBand b = weft::tileRows(height, i, count);
                EXPECT_EQ(b.begin, next) << height << " " << i << "/" << count;
                EXPECT_GE(b.end - b.begin, height / count);
                EXPECT_LE(b.end - b.begin, height / count + 1);
                next = b.end;
            }
            EXPECT_EQ(next, height);
        }
    EXPECT_THROW(weft::tileRows(4, 1, 5), weft::Error);
}

TEST(TileSpec, ParsesIOfNAndRejectsTheRest) {
    EXPECT_EQ(weft::parseTileSpec("2/4"), (weft::TileSpec{2, 4}));
    EXPECT_EQ(weft::parseTileSpec("1/1"), (weft::TileSpec{1, 1}));
    for (const char* bad : {"0/4", "5/4", "2", "2/", "/4", "2/4x", "-1/4", "a/b", "2-4"})
        EXPECT_THROW(weft::parseTileSpec(bad), weft::Error) << bad;
}

}  // namespace
