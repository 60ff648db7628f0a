// weft pattern: the published discrepancies as printed, the files it
// writes, and one-line errors that leave no output behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "core/image/io/image_io.hpp"
#include "tests/support/test_support.hpp"

using namespace weft::test;

namespace {

double printedDiscrepancy(const std::string& args) {
    const CommandResult r = runWeft("pattern " + args);
    EXPECT_EQ(r.status, 0) << r.output;
    const auto at = r.output.find("L2-star discrepancy");
    return at == std::string::npos ? -1 : std::stod(r.output.substr(at + 20));
}

}  // namespace

TEST(PatternCli, PrintsThePublishedDiscrepancies) {
    EXPECT_NEAR(printedDiscrepancy("regular --count 16"), 0.0597258, 5e-7);
    EXPECT_NEAR(printedDiscrepancy("hammersley --count 16"), 0.0692908, 5e-7);
    EXPECT_NEAR(printedDiscrepancy("hammersley --count 256"), 0.00627723, 5e-9);
}

TEST(PatternCli, WritesPeriodogramRadialCsvPointsAndPreview) {
    TempDir dir;
    const CommandResult r = runWeft("pattern interleaved:2x2,basis=lp --count 4 --seeds 4 -o " + (dir / "p.exr").string() +
                                    " --points " + (dir / "pts.csv").string() + " --preview " + (dir / "p.png").string());
    ASSERT_EQ(r.status, 0) << r.output;
    const weft::Image img = weft::readImage((dir / "p.exr").string());
    EXPECT_EQ(img.width(), 33);  // R = max(16, 2 sqrt(16))
    EXPECT_NEAR(img.at(16, 16, 0), 16.0f, 1e-4);  // DC: the number of points
    std::ifstream csv(dir / "p_radial.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header.rfind("frequency_per_tile,", 0), 0u);
    const std::string pts = readBytes(dir / "pts.csv");
    EXPECT_EQ(std::count(pts.begin(), pts.end(), '\n'), 17);
    EXPECT_TRUE(std::filesystem::exists(dir / "p.png"));
}

TEST(PatternCli, ErrorsAreOneLineAndLeaveNoFile) {
    TempDir dir;
    for (const char* args : {"blue --count 4", "poisson,radius=3 --count 4", "interleaved:2x --count 4",
                             "interleaved:2x2 --tile 4x4 --count 4"}) {
        const CommandResult r = runWeft(std::string("pattern ") + args + " -o " + (dir / "x.exr").string());
        EXPECT_NE(r.status, 0) << args;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_EQ(r.output.rfind("weft: error: ", 0), 0u) << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "x.exr")) << args;
    }
}
