// Counters are declared once as handles (core/base/run/counters.hpp): every name
// a render records is a declared one, each name is declared once, and `weft
// help counters` lists them with their meaning.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>

#include "core/base/run/counters.hpp"
#include "tests/support/test_support.hpp"

using namespace weft::test;

namespace {

const weft::Counter kTestCounted{"test.counted", "counted by counters_test only"};
const weft::IndexedCounter kTestLevel{"test.level", "counted by counters_test only, per level"};

bool declared(const std::string& name) {
    for (const auto& [declaredName, doc] : weft::declaredCounters()) {
        if (declaredName == name) return true;
        const auto n = declaredName.find("<N>");
        if (n != std::string::npos && name.rfind(declaredName.substr(0, n), 0) == 0 && name.size() > n &&
            name.find_first_not_of("0123456789", n) == std::string::npos)
            return true;
    }
    return false;
}

TEST(Counters, HandlesAddUnderTheirNamesAndIndexedOnesPerIndex) {
    weft::Counters c;
    c.add(kTestCounted, 3), c.add(kTestCounted, 4);
    c.add(kTestLevel, 0, 5), c.add(kTestLevel, 12, 6);
    const weft::CounterMap m = c.merged();
    EXPECT_EQ(m, (weft::CounterMap{{"test.counted", 7}, {"test.level0", 5}, {"test.level12", 6}}));
    EXPECT_EQ(c.total("test.counted"), 7);
}

TEST(Counters, EachNameIsDeclaredOnceWithAMeaning) {
    std::set<std::string> names;
    for (const auto& [name, doc] : weft::declaredCounters()) {
        EXPECT_TRUE(names.insert(name).second) << name << " is declared twice";
        EXPECT_FALSE(doc.empty()) << name;
    }
    for (const char* name : {"rays.camera", "rays.shadow", "volume.samples", "volume.samples.level<N>", "image.nonfinite"})
        EXPECT_TRUE(names.count(name)) << name;
}

// The names in stats JSON stay what bench scripts read, and all are declared.
TEST(Counters, EveryRecordedCounterIsDeclared) {
    TempDir dir;
    for (const std::string technique : {"volume.raymarch", "volume.adaptive3d", "volume.preint"}) {
        const std::string stats = (dir / (technique + ".json")).string();
        const auto r = runWeft("render builtin:cloud --res 16x16 --technique " + technique + " --stats " + stats);
        ASSERT_EQ(r.status, 0) << r.output;
        const nlohmann::json j = nlohmann::json::parse(readBytes(stats));
        ASSERT_FALSE(j["counters"].empty()) << technique;
        EXPECT_TRUE(j["counters"].contains("volume.samples")) << technique;
        for (const auto& item : j["counters"].items()) EXPECT_TRUE(declared(item.key())) << technique << ": " << item.key();
        if (technique == "volume.adaptive3d") {
            EXPECT_TRUE(j["counters"].contains("volume.samples.level0"));
        }
    }
}

TEST(Counters, HelpCountersListsThemWithTheirMeaning) {
    const auto r = runWeft("help counters");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("rays.camera"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("camera rays"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("volume.samples.level<N>"), std::string::npos) << r.output;
}

}  // namespace
