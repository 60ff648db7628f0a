// Cost models: every shipped profile declares one, bad ones are clear
// errors, and the speed-ups bench/hwsim_calibrate.py recorded for the Mesa
// profiles (hwsim/profiles/calibration/*.json) are still what hwsim's counts
// and the profiles' cost terms predict. Measured times are never compared.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/base/error.hpp"
#include "hwsim/replay.hpp"

namespace weft::hwsim {
namespace {

std::string errorOf(const std::string& text) {
    try {
        parseCostModel(text, "p.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(HwsimCostModel, EveryShippedProfileDeclaresOne) {
    const std::string fallback = CostModel{}.calibration;
    for (const Profile& p : builtinProfiles()) {
        EXPECT_NE(p.cost.calibration, fallback) << p.name << " has no cost_model";
        EXPECT_FALSE(p.cost.nsPer.empty()) << p.name;
    }
    EXPECT_EQ(findProfile("mesa-llvmpipe").cost.calibration.rfind("calibrated", 0), 0u);
    EXPECT_EQ(findProfile("mesa-softpipe").cost.calibration.rfind("calibrated", 0), 0u);
}

TEST(HwsimCostModel, BadModelsNameWhatIsWrong) {
    EXPECT_EQ(errorOf(R"({"calibration": "c", "ns_per": {"passes": 1000, "fragment_program.cost": 0.5}})"), "");
    EXPECT_EQ(errorOf(R"({"calibration": "c", "ns_per": {"texture.scattered_fetches": 300}})"), "");  // a replay's own counter
    EXPECT_NE(errorOf(R"({"ns_per": {"passes": 1}})").find("exactly 'calibration'"), std::string::npos);
    EXPECT_NE(errorOf(R"({"calibration": "c", "ns_per": {"fragments": 1}})").find("unknown counter 'fragments'"), std::string::npos);
    EXPECT_NE(errorOf(R"({"calibration": "c", "ns_per": {"passes": -1}})").find("passes must be a number >= 0"), std::string::npos);
    EXPECT_NE(errorOf(R"({"calibration": "c", "ns_per": {}})").find("non-empty"), std::string::npos);
}

TEST(HwsimCostModel, PredictsTheSumOfCountsTimesTerms) {
    const CostModel m = parseCostModel(R"({"calibration": "c", "ns_per": {"passes": 1000, "fragment_program.cost": 0.5}})", "p.json");
    const CounterMap counts{{"passes", 4}, {"fragment_program.cost", 2000000}, {"fragments.generated", 7}};
    EXPECT_DOUBLE_EQ(predictedMs(m, counts), (4 * 1000 + 0.5 * 2000000) * 1e-6);
}

// llvmpipe runs 8-wide vectors over 4x2 pixels whole (lock_step_whole_block):
// a 4x4 stencil pattern still runs one vector in two, and a light skipped by
// a branch costs its vector one unit per lane.
TEST(HwsimCostModel, LlvmpipeVectorsRunWhole) {
    const ReplayResult r = runReplay("segovia.table1", findProfile("mesa-llvmpipe"), {{"width", "64"}, {"height", "64"}, {"light_cost", "10"}});
    const auto cost = [&](const std::string& label) {
        for (const ReplayVariant& v : r.variants)
            if (v.label == label) return v.counters.at("fragment_program.cost");
        throw Error("no variant " + label);
    };
    const std::int64_t lights = 16, blocks4x4 = 64 * 64 / 16;
    EXPECT_EQ(cost("none"), lights * blocks4x4 * 16 * 10);
    EXPECT_EQ(cost("stencil 4x4"), lights * blocks4x4 * 8 * 10);
    EXPECT_EQ(cost("branch 4x4"), lights * blocks4x4 * (8 * 10 + 8 * 1));
    EXPECT_EQ(cost("stencil 2x2"), cost("none"));
}

TEST(HwsimCostModel, CalibrationsStillPredictTheirRecordedSpeedups) {
    for (const std::string name : {"mesa-llvmpipe", "mesa-softpipe", "nvidia-h200"}) {
        std::ifstream in(std::string(WEFT_SOURCE_DIR) + "/hwsim/profiles/calibration/" + name + ".json");
        ASSERT_TRUE(in) << "no calibration record for " << name;
        const nlohmann::json record = nlohmann::json::parse(in);
        const Profile& profile = findProfile(name);
        std::map<std::pair<std::string, int>, ReplayResult> runs;
        for (const nlohmann::json& row : record.at("rows")) {
            const std::string replay = row.at("replay");
            const int size = row.at("size");
            auto it = runs.find({replay, size});
            if (it == runs.end()) {
                std::map<std::string, std::string> params{{"width", std::to_string(size)}, {"height", std::to_string(size)}};
                if (record.at("params").contains(replay))
                    for (const auto& [k, v] : record["params"][replay].items()) params[k] = v.dump();
                it = runs.emplace(std::pair{replay, size}, runReplay(replay, profile, params)).first;
            }
            const ReplayResult& r = it->second;
            const double base = predictedMs(profile.cost, r.variants[baselineIndex(r)].counters);
            const std::string label = row.at("variant");
            const auto v = std::find_if(r.variants.begin(), r.variants.end(), [&](const ReplayVariant& x) { return x.label == label; });
            ASSERT_NE(v, r.variants.end()) << replay << " has no variant " << label;
            const double ms = predictedMs(profile.cost, v->counters);
            const std::string where = name + " " + replay + " " + std::to_string(size) + " " + label;
            EXPECT_NEAR(ms, row.at("predicted_ms").get<double>(), 1e-5 + 1e-6 * ms) << where;
            EXPECT_NEAR(base / ms, row.at("predicted_speedup").get<double>(), 1e-5) << where;
        }
    }
}

}  // namespace
}  // namespace weft::hwsim
