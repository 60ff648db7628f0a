// weft sampling-report and the analytic built-in scenes from the command line.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/image/io/image_io.hpp"
#include "tests/support/test_support.hpp"

using namespace weft::test;

TEST(SamplingReportCli, PrintsTheTableAndWritesOneCsvRowPerMeasurement) {
    TempDir dir;
    const CommandResult r = runWeft("sampling-report --scene grating --scene disc --res 32x32 --spp 1,4 --pattern regular "
                                    "--pattern interleaved:2x2,basis=lp --pattern none -o " + (dir / "r.csv").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("interleaved:2x2,basis=lp"), std::string::npos);
    const std::string csv = readBytes(dir / "r.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 3 * 2);
    EXPECT_EQ(csv.rfind("scene,pattern,spp,rmse,aliasing_peak_ratio,peak_fx,peak_fy,blurred_rmse\n", 0), 0u);
}

TEST(SamplingReportCli, BadCountsAndPatternsAreOneLineErrors) {
    TempDir dir;
    for (const char* args : {"--spp 0", "--spp 4,x", "--pattern blue", "--scene mandrill"}) {
        const CommandResult r = runWeft(std::string("sampling-report --res 8x8 ") + args + " -o " + (dir / "r.csv").string());
        EXPECT_NE(r.status, 0) << args;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "r.csv")) << args;
    }
}

TEST(AnalyticCli, BuiltinScenesRenderWithPatternsAndRecordThem) {
    TempDir dir;
    const CommandResult r = runWeft("render builtin:zoneplate --res 32x32 --spp 4 --set pattern=interleaved:4x4,basis=jitter -o " +
                                    (dir / "z.exr").string());
    ASSERT_EQ(r.status, 0) << r.output;
    weft::Metadata md;
    const weft::Image img = weft::readImage((dir / "z.exr").string(), &md);
    EXPECT_EQ(img.width(), 32);
    bool recorded = false;
    for (const auto& [k, v] : md) recorded |= k == "weft:param:pattern" && v == "interleaved:4x4,basis=jitter";
    EXPECT_TRUE(recorded);
}
