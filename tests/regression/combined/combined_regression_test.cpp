// Image regressions of the combined scenes (volumes and meshes together):
// every folder under tests/regression/combined/ with a case.json and its
// ref.exr, judged by the rule in case.json (the same rule run.sh applies).
// Regenerate deliberately with tests/regression/combined/run.sh --update.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/image/io/image_io.hpp"
#include "core/image/compare/regression_case.hpp"
#include "plugins/host/render_job.hpp"

using namespace weft;
namespace fs = std::filesystem;

namespace {

const fs::path kRoot = WEFT_SOURCE_DIR;

std::vector<std::string> caseNames() {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(kRoot / "tests/regression/combined"))
        if (fs::exists(e.path() / "case.json")) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

class CombinedRegression : public ::testing::TestWithParam<std::string> {};

RenderRequest requestOf(const RegressionCase& c, int threads) {
    RenderRequest r;
    r.input = (kRoot / c.input).string();
    r.technique = c.technique;
    r.resolution = parseResolution(c.resolution);
    r.spp = c.spp;
    r.sets = c.sets;
    r.threads = threads;
    return r;
}

fs::path caseDir(const std::string& name) { return kRoot / "tests/regression/combined" / name; }

}  // namespace

TEST_P(CombinedRegression, MatchesReference) {
    const fs::path dir = caseDir(GetParam());
    const RegressionCase c = readRegressionCase((dir / "case.json").string());
    const Image img = renderToImage(requestOf(c, 0)).image;
    const Image ref = readImage((dir / "ref.exr").string());
    EXPECT_EQ(regressionVerdict(compareImages(img, ref, c.rule.threshold), c.rule), "");
    float alphaSum = 0;
    for (int y = 0; y < ref.height(); ++y)
        for (int x = 0; x < ref.width(); ++x) alphaSum += ref.at(x, y, 3);
    EXPECT_GT(alphaSum, 0.05f * float(ref.width() * ref.height()));  // the reference is not empty
}

GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(CombinedRegression);  // a fresh checkout may hold no case yet
TEST_P(CombinedRegression, SameImageOnOneAndTwoThreads) {
    const RegressionCase c = readRegressionCase((caseDir(GetParam()) / "case.json").string());
    EXPECT_EQ(renderToImage(requestOf(c, 1)).image.data(), renderToImage(requestOf(c, 2)).image.data());
}

INSTANTIATE_TEST_SUITE_P(Scenes, CombinedRegression, ::testing::ValuesIn(caseNames()),
                         [](const auto& info) { return info.param; });

TEST(RegressionRule, FailsOnFractionOrHardLimit) {
    ImageComparison c;
    c.pixels = 100, c.pixelsAbove = 2, c.overall.maxAbs = 0.01;
    EXPECT_EQ(regressionVerdict(c, {}), "");
    c.pixelsAbove = 3;
    EXPECT_NE(regressionVerdict(c, {}).find("3 of 100 pixels"), std::string::npos);
    c.pixelsAbove = 0, c.overall.maxAbs = 0.02;
    EXPECT_NE(regressionVerdict(c, {}).find("hard limit"), std::string::npos);
}
