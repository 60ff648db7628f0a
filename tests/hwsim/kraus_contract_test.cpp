// The contract between core and hwsim: kraus.fig4 and kraus.fig9, run
// through the modelled pipeline under any profile, give volume.adaptive3d's
// image bit for bit and the same number of volume samples — with the
// minimum oracle and with a test oracle whose distances vary, so that the
// bounds and depth tests make real decisions.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/error.hpp"
#include "core/image/compare/image_compare.hpp"
#include "hwsim/replay.hpp"
#include "oracles/oracle.hpp"
#include "tests/support/render_helpers.hpp"

namespace weft {
namespace {

// Distances between 1 and 9 slices, varying in waves across the volume
// (in 64 steps: index i holds 1 + i / 8 slices).
const OracleRegistrar wavyOracle{{"test.hwsim_wavy", "test: distances in waves of 1..9 slices", [](const OracleContext& ctx) {
    OracleField f;
    auto rings = std::make_shared<RingTree>(kFarRing);
    f.distances.assign(256, float(8 * ctx.sliceSpacing));
    for (int i = 0; i <= 64; ++i) f.distances[i] = float((1 + i / 8.0) * ctx.sliceSpacing);
    const openvdb::CoordBBox box = ctx.volume.grid->evalActiveVoxelBoundingBox();
    openvdb::tree::ValueAccessor<RingTree> acc(*rings);
    for (auto it = box.begin(); it != box.end(); ++it) {
        const openvdb::Coord c = *it;
        const double wave = 0.5 + 0.5 * std::sin(c.x() * 0.35) * std::cos(c.y() * 0.25 + c.z() * 0.1);
        acc.setValue(c, std::uint8_t(std::lround(64 * wave)));
    }
    f.rings = rings;
    return f;
}}};

struct Core {
    Image image;
    std::int64_t samples;
};

// Slices 4 voxels apart are wider than these pixels, so the oracle's
// distances count in slices and the skipping is real.
Core coreRender(const std::string& oracle) {
    const RenderOutcome out =
        test::render("builtin:cloud", "44x36", {"oracle=" + oracle, "lmax=3", "spacing=4"}, "volume.adaptive3d");
    return {out.image, out.counters.at("volume.samples")};
}

void expectContract(const std::string& replay, const std::string& profile, const std::string& oracle, const Core& core) {
    const hwsim::ReplayResult r = hwsim::runReplay(
        replay, hwsim::findProfile(profile), {{"width", "44"}, {"height", "36"}, {"oracle", oracle}, {"lmax", "3"}, {"spacing", "4"}});
    ASSERT_TRUE(r.image.has_value());
    const ImageComparison cmp = compareImages(*r.image, core.image);
    EXPECT_EQ(cmp.overall.maxAbs, 0.0) << replay << " " << profile << " " << oracle;
    EXPECT_EQ(r.variants.at(0).counters.at("volume.samples"), core.samples) << replay << " " << profile << " " << oracle;
}

TEST(HwsimKraus, ReplaysGiveTheCoreImageAndSamples) {
    for (const char* oracle : {"test.hwsim_wavy", "minimum"}) {
        const Core core = coreRender(oracle);
        for (const char* profile : {"ideal", "geforce-7800", "modern-desktop"})
            for (const char* replay : {"kraus.fig4", "kraus.fig9"}) expectContract(replay, profile, oracle, core);
    }
}

// The core passes over tiles whose pixels and parents hold nothing but the
// background at the longest distance (the cloud's empty surroundings); the
// replays visit every due pixel. The image and samples stay the same, the
// syntheses are fewer.
TEST(HwsimKraus, QuietTilesPassedOverKeepTheImage) {
    const RenderOutcome core = test::render("builtin:cloud", "256x208", {"oracle=gradient_alpha", "lmax=3"}, "volume.adaptive3d");
    const hwsim::ReplayResult r = hwsim::runReplay(
        "kraus.fig4", hwsim::findProfile("ideal"), {{"width", "256"}, {"height", "208"}, {"oracle", "gradient_alpha"}, {"lmax", "3"}});
    ASSERT_TRUE(r.image.has_value());
    EXPECT_EQ(compareImages(*r.image, core.image).overall.maxAbs, 0.0);
    const CounterMap& replay = r.variants.at(0).counters;
    EXPECT_EQ(replay.at("volume.samples"), core.counters.at("volume.samples"));
    EXPECT_EQ(replay.at("composite.ops"), core.counters.at("composite.ops"));
    EXPECT_LT(core.counters.at("synthesis.ops"), replay.at("synthesis.ops") * 3 / 4);
}

TEST(HwsimKraus, TheWavyOracleSkipsSamples) {
    EXPECT_LT(coreRender("test.hwsim_wavy").samples, coreRender("minimum").samples * 2 / 3);
}

TEST(HwsimKraus, Fig4NeedsDepthBoundsFig9DoesNot) {
    const std::map<std::string, std::string> p{{"width", "16"}, {"height", "16"}, {"oracle", "minimum"}};
    try {
        hwsim::runReplay("kraus.fig4", hwsim::findProfile("mesa-llvmpipe"), p);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("depth bounds test"), std::string::npos) << e.what();
    }
    EXPECT_NO_THROW(hwsim::runReplay("kraus.fig9", hwsim::findProfile("mesa-llvmpipe"), p));
}

// Figure 4's bounds change every pass: the GeForce 7800 profile loses the
// early test (the paper's finding), the ideal one keeps it; Figure 9's
// depth test stays early on hardware with per-pixel early tests.
TEST(HwsimKraus, EarlyRejectionFollowsTheProfile) {
    const std::map<std::string, std::string> p{{"width", "32"}, {"height", "32"}, {"oracle", "test.hwsim_wavy"}};
    auto run = [&](const char* replay, const char* profile) {
        return hwsim::runReplay(replay, hwsim::findProfile(profile), p).variants.at(0).counters;
    };
    const CounterMap idealFig4 = run("kraus.fig4", "ideal"), gf4 = run("kraus.fig4", "geforce-7800");
    EXPECT_GT(idealFig4.at("fragments.rejected.bounds"), 0);
    EXPECT_EQ(idealFig4.at("fragment_program.invocations"), idealFig4.at("samples.passed"));
    EXPECT_GT(gf4.at("fragment_program.invocations"), gf4.at("samples.passed"));
    const CounterMap idealFig9 = run("kraus.fig9", "ideal"), modernFig9 = run("kraus.fig9", "modern-desktop");
    EXPECT_GT(idealFig9.at("fragments.rejected.depth_early"), 0);
    EXPECT_EQ(idealFig9.at("fragments.rejected.depth_late"), 0);
    EXPECT_EQ(modernFig9.at("fragments.rejected.depth_late"), 0);
    EXPECT_GT(modernFig9.at("coarse.tiles_culled"), 0);
}

}  // namespace
}  // namespace weft
