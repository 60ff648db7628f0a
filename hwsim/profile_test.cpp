// Hardware profiles: the shipped files load, and bad files are clear errors.
#include <gtest/gtest.h>

#include "core/base/error.hpp"
#include "hwsim/profile.hpp"

namespace weft::hwsim {
namespace {

TEST(HwsimProfile, ShipsTheDocumentedProfiles) {
    std::vector<std::string> names;
    for (const Profile& p : builtinProfiles()) names.push_back(p.name);
    EXPECT_EQ(names, (std::vector<std::string>{"geforce-7800", "ideal", "mesa-llvmpipe", "mesa-softpipe", "modern-desktop", "nvidia-h200"}));
    EXPECT_EQ(findProfile("mesa-llvmpipe").bounds, BoundsSupport::Unsupported);
    EXPECT_EQ(findProfile("geforce-7800").earlyTests, EarlyTests::CoarseOnly);
    EXPECT_EQ(findProfile("ideal").shading, ShadingGranularity::Pixel);
    const Profile& llvmpipe = findProfile("mesa-llvmpipe");
    EXPECT_TRUE(llvmpipe.statsCountedAtScan);
    EXPECT_EQ(llvmpipe.statsStampW * llvmpipe.statsStampH, 16);
    EXPECT_TRUE(findProfile("mesa-softpipe").clippingOutputSkipsZeroArea);
    EXPECT_EQ(findProfile("modern-desktop").statsStampW, 2);  // "quads"
}

std::string errorOf(const std::string& text) {
    try {
        parseProfile(text, "p.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(HwsimProfile, BadFilesNameKeyAndValidValues) {
    EXPECT_NE(errorOf("{").find("p.json"), std::string::npos);
    EXPECT_NE(errorOf("{\"name\": \"x\"}").find("missing key 'description'"), std::string::npos);
    const std::string base = R"({"name":"x","description":"d","sources":"s","fill_rule":"top_left","scan":"edge_functions","stipple":"rasterizer",
      "polygon_stipple":true,"stipple_mirrored_when_program_reads_position":false,"early_tests":"per_pixel","early_tests_need_depth_test":false,"early_rejected_quads_still_run":false,"coarse_tile":0,
      "coarse_stencil":false,"depth_bounds":"early","bounds_change_forces_late":false,
      "depth_direction_change_disables_coarse":false,"discard_forces_late":"never","side_effects_force_late":true,"query_counts_at_early_tests":true,
      "shading":"pixel","shader_invocations_counter":"pixels","shader_invocations_counted_at":"program",
      "clipping_output_counts_zero_area":true,"branch_block":[1,1])";
    EXPECT_EQ(errorOf(base + "}"), "");
    EXPECT_NE(errorOf(base + ",\"colour\":1}").find("unknown key 'colour'"), std::string::npos);
    std::string badStipple = base + "}";
    badStipple.replace(badStipple.find("\"rasterizer\""), 12, "\"sometimes\"");
    EXPECT_NE(errorOf(badStipple).find("not one of rasterizer|program_start|late"), std::string::npos);
    std::string badTile = base + "}";
    badTile.replace(badTile.find("\"coarse_tile\":0"), 15, "\"coarse_tile\":6");
    EXPECT_NE(errorOf(badTile).find("power of two"), std::string::npos);
    std::string badCounter = base + "}";
    badCounter.replace(badCounter.find("\"pixels\""), 8, "[4, 3]");
    EXPECT_NE(errorOf(badCounter).find("'shader_invocations_counter' 3 must be 0 or a power of two"), std::string::npos);
    badCounter.replace(badCounter.find("[4, 3]"), 6, "\"warps\"");
    EXPECT_NE(errorOf(badCounter).find("must be pixels|quads or a stamp [width, height]"), std::string::npos);
    EXPECT_THROW(findProfile("voodoo2"), Error);
}

}  // namespace
}  // namespace weft::hwsim
