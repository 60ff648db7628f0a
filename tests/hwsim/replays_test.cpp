// The paper replays: exact counts where they follow from the pass structure,
// the papers' conclusions under the profiles of their hardware, and profiles
// that change only what they should (never which samples pass or the image).
#include <gtest/gtest.h>

#include "core/base/error.hpp"
#include "hwsim/replay.hpp"
#include "tests/support/test_support.hpp"

namespace weft::hwsim {
namespace {

const CounterMap& variant(const ReplayResult& r, const std::string& label) {
    for (const ReplayVariant& v : r.variants)
        if (v.label == label) return v.counters;
    throw Error("no variant " + label);
}

std::int64_t at(const ReplayResult& r, const std::string& label, const std::string& counter) {
    return variant(r, label).at(counter);
}

ReplayResult segovia(const std::string& profile) {
    return runReplay("segovia.table1", findProfile(profile), {{"width", "64"}, {"height", "64"}, {"light_cost", "10"}});
}

constexpr std::int64_t kN = 64 * 64, kLights = 16, kCost = 10;

TEST(HwsimSegovia, IdealHardwareWouldGainFromEveryMethod) {
    const ReplayResult r = segovia("ideal");
    EXPECT_EQ(at(r, "none", "fragment_program.invocations"), kLights * kN);
    EXPECT_EQ(at(r, "stencil 4x4", "fragment_program.invocations"), kLights * kN / 16);
    EXPECT_EQ(at(r, "depth 2x2", "fragment_program.invocations"), kLights * kN / 4);
    EXPECT_EQ(at(r, "branch 4x4", "fragment_program.cost"), kLights * (kN / 16 * kCost + kN * 15 / 16));
    EXPECT_EQ(at(r, "split 4x4", "fragment_program.invocations"), kN + kLights * kN / 16 + kN);
}

// Only the split and gather copies fetch through the interleave's
// permutation: one scattered fetch per pixel each, whatever the pattern.
TEST(HwsimSegovia, SplitAndGatherFetchEveryTexelScattered) {
    const ReplayResult r = segovia("mesa-softpipe");
    for (const char* n : {"2x2", "4x4"}) {
        EXPECT_EQ(at(r, "split " + std::string(n), "texture.scattered_fetches"), 2 * kN) << n;
        for (const char* m : {"stencil ", "depth ", "branch "}) EXPECT_EQ(at(r, m + std::string(n), "texture.scattered_fetches"), 0) << m << n;
    }
    EXPECT_EQ(at(r, "none", "texture.scattered_fetches"), 0);
}

TEST(HwsimSegovia, OnTheGeforce7800OnlySplittingPays) {
    const ReplayResult r = segovia("geforce-7800");
    const std::int64_t full = at(r, "none", "fragment_program.cost");
    EXPECT_EQ(full, kLights * kN * kCost);
    for (const char* n : {"2x2", "4x4"}) {
        for (const char* m : {"stencil ", "depth ", "branch "}) EXPECT_EQ(at(r, m + std::string(n), "fragment_program.cost"), full) << m << n;
        EXPECT_LT(at(r, "split " + std::string(n), "fragment_program.cost"), full / 3) << n;
        EXPECT_EQ(at(r, "stencil " + std::string(n), "coarse.tiles_culled"), 0);  // every 8x8 tile holds every class
    }
}

TEST(HwsimSegovia, QuadShadingWastesTheCulledLanes) {
    const ReplayResult r = segovia("modern-desktop");
    EXPECT_EQ(at(r, "stencil 2x2", "fragment_program.invocations"), kLights * kN);  // one live pixel per quad
    EXPECT_EQ(at(r, "stencil 2x2", "fragment_program.helpers"), kLights * kN * 3 / 4);
    EXPECT_EQ(at(r, "stencil 4x4", "fragment_program.invocations"), kLights * kN / 4);
    EXPECT_EQ(at(r, "branch 2x2", "fragment_program.cost"), kLights * kN * kCost);  // 8x4 warps always mixed
}

TEST(HwsimSegovia, InterleavedVariantsMakeOneImage) {
    const ReplayResult r = segovia("modern-desktop");
    for (const std::string& note : r.notes) EXPECT_NE(note.find("identical"), std::string::npos) << note;
    ASSERT_TRUE(r.image.has_value());
    EXPECT_EQ(r.image->width(), 64);
}

TEST(HwsimKeller, StippleGainsOnlyWhenRejectedAtScanConversion) {
    const std::map<std::string, std::string> params{{"width", "128"}, {"height", "128"}, {"n", "4"}, {"triangles", "24"}};
    const ReplayResult ideal = runReplay("keller.stipple", findProfile("ideal"), params);
    const ReplayResult late = runReplay("keller.stipple", findProfile("geforce-7800"), params);
    const std::int64_t superIdeal = at(ideal, "supersampled", "fragment_program.invocations");
    EXPECT_LT(at(ideal, "interleaved", "fragment_program.invocations"), superIdeal / 16 * 5 / 4);
    EXPECT_GE(at(late, "interleaved", "fragment_program.invocations"), at(late, "supersampled", "fragment_program.invocations"));
    EXPECT_EQ(at(ideal, "interleaved", "fragments.generated"), at(ideal, "supersampled", "fragments.generated"));
}

// What passes and what is written is the API's business; profiles may only
// move work between stages — except for the rasterization rules, which GL
// leaves to the implementation, so profiles are compared with one that
// shares them.
TEST(HwsimProfiles, ChangeCostsButNeverResults) {
    for (const char* replay : {"keller.stipple", "segovia.table1"}) {
        const std::map<std::string, std::string> params{{"width", "64"}, {"height", "64"}};
        std::map<std::pair<int, bool>, ReplayResult> refs;  // by (fill rule, scan)
        int compared = 0;
        for (const Profile& p : builtinProfiles()) {
            const ReplayResult r = runReplay(replay, p, params);
            const auto [it, first] = refs.emplace(std::make_pair(int(p.fillRule), p.floatSpans), r);
            const ReplayResult& ref = it->second;
            compared += !first;
            ASSERT_EQ(r.variants.size(), ref.variants.size());
            for (std::size_t i = 0; i < r.variants.size(); ++i)
                for (const char* c : {"fragments.generated", "samples.passed", "pixels.written"})
                    EXPECT_EQ(r.variants[i].counters.at(c), ref.variants[i].counters.at(c)) << replay << " " << p.name << " " << c;
        }
        EXPECT_GE(compared, 2) << replay;  // ideal, geforce-7800 and modern-desktop share theirs
    }
}

TEST(HwsimCli, ListsProfilesAndWritesStats) {
    const test::CommandResult list = test::runWeft("hwsim --list-profiles");
    EXPECT_EQ(list.status, 0);
    for (const char* name : {"ideal", "mesa-llvmpipe", "mesa-softpipe", "geforce-7800", "modern-desktop", "nvidia-h200"})
        EXPECT_NE(list.output.find(name), std::string::npos) << name;
    test::TempDir dir;
    const test::CommandResult run = test::runWeft("hwsim segovia.table1 --profile geforce-7800 --set width=32 --set height=32 --stats " +
                                                  (dir / "s.json").string());
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("fragments.rejected.depth_late"), std::string::npos);
    const std::string json = test::readBytes(dir / "s.json");
    EXPECT_NE(json.find("\"fragment_program.invocations\""), std::string::npos);
    EXPECT_NE(json.find("\"profile\": \"geforce-7800\""), std::string::npos);
    const test::CommandResult bad = test::runWeft("hwsim segovia.table1 --profile voodoo2");
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.output.find("unknown hwsim profile 'voodoo2'"), std::string::npos);
    const test::CommandResult badKey = test::runWeft("hwsim keller.stipple --set n=3");
    EXPECT_EQ(badKey.status, 1);
    EXPECT_NE(badKey.output.find("n"), std::string::npos);
}

TEST(HwsimCli, MissingFeatureFailsClearlyWithoutOutputs) {
    test::TempDir dir;
    const test::CommandResult r = test::runWeft("hwsim kraus.fig4 --profile mesa-llvmpipe --set oracle=minimum --stats " +
                                                (dir / "s.json").string() + " -o " + (dir / "i.exr").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("kraus.fig4 needs the depth bounds test"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("'mesa-llvmpipe'"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "s.json"));
    EXPECT_FALSE(std::filesystem::exists(dir / "i.exr"));
}

}  // namespace
}  // namespace weft::hwsim
