// weft tune: the setting it prints, rendered again with the command line it
// prints, meets the target; the search's midpoints and targets parse as
// documented; bad targets are one line.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/image/io/image_io.hpp"
#include "plugins/host/trade/trade_metrics.hpp"
#include "plugins/host/trade/tune_search.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;
using namespace weft::test;

TEST(TuneCli, PrintedCommandMeetsTheTarget) {
    TempDir dir;
    const std::string cache = " --cache " + (dir / "refs").string();
    const auto out = runWeft("tune builtin:sphere --res 24x16 --technique volume.raymarch --technique volume.preint --target rmse=0.02" +
                             cache + " --json " + (dir / "choice.json").string());
    ASSERT_EQ(out.status, 0) << out.output;
    std::ifstream in(dir / "choice.json");
    const auto j = nlohmann::json::parse(in);
    ASSERT_TRUE(j["met"].get<bool>()) << out.output;
    EXPECT_LE(j["choice"]["error"]["rmse"].get<double>(), 0.02);
    EXPECT_EQ(j["techniques"].size(), 2u);
    std::string command = j["choice"]["command"];
    ASSERT_EQ(command.rfind("weft render ", 0), 0u) << command;
    EXPECT_NE(out.output.find(command), std::string::npos) << out.output;
    command.replace(command.find("-o out.exr"), 10, "-o " + (dir / "again.exr").string());
    ASSERT_EQ(runWeft(command.substr(5)).status, 0) << command;
    std::vector<std::filesystem::path> refs;
    for (const auto& e : std::filesystem::directory_iterator(dir / "refs")) refs.push_back(e.path());
    ASSERT_EQ(refs.size(), 1u);  // raymarch and preint share their family's reference
    const TradeError e = measureTradeError(readImage((dir / "again.exr").string()), readImage(refs[0].string()));
    EXPECT_LE(e.rmse, 0.02);
}

TEST(TuneCli, BadTargetsAreOneLine) {
    for (const char* target : {"rmse", "rmse=-1", "mse=0.1", "rmse=abc"}) {
        const auto out = runWeft(std::string("tune builtin:sphere --res 8x8 --target ") + target);
        EXPECT_NE(out.status, 0) << target;
        EXPECT_NE(out.output.find("--target"), std::string::npos) << target << ": " << out.output;
        EXPECT_EQ(std::count(out.output.begin(), out.output.end(), '\n'), 1) << out.output;
    }
    const auto both = runWeft("tune builtin:sphere --res 8x8 --target rmse=0.1 --metric psnr");
    EXPECT_NE(both.output.find("different metrics"), std::string::npos) << both.output;
}

TEST(TuneSearch, MidpointsAndTargets) {
    EXPECT_EQ(knobMidpoint("1", "4"), "2");
    EXPECT_EQ(knobMidpoint("0.5", "2"), "1");
    EXPECT_EQ(knobMidpoint("4", "5"), std::nullopt);  // no integer strictly between
    EXPECT_EQ(knobMidpoint("8x8", "4x4"), std::nullopt);
    EXPECT_EQ(knobMidpoint("0", "1"), std::nullopt);
    const TuneTarget rmse = parseTuneTarget("rmse=0.01");
    EXPECT_TRUE(rmse.met(TradeError{0.01, 0, 0, 0, 0, 0}));
    EXPECT_FALSE(rmse.met(TradeError{0.011, 0, 0, 0, 0, 0}));
    const TuneTarget psnr = parseTuneTarget("psnr=40");
    EXPECT_TRUE(psnr.met(TradeError{0, 0, 41, 0, 0, 0}));
    EXPECT_FALSE(psnr.met(TradeError{0, 0, 39, 0, 0, 0}));
}
