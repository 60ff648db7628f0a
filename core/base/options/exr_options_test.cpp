// The EXR encoding options: -d specs select channels by name, layer or
// `aovs`, later ones win, bad specs are one line naming the spec; the pixel
// types are summarised for the metadata.
#include "core/base/options/exr_options.hpp"

#include <gtest/gtest.h>

#include "core/base/error.hpp"
#include "tests/support/test_support.hpp"

namespace weft {
namespace {

const std::vector<std::string> kChannels{"R", "G", "B", "A", "N.X", "N.Y", "N.Z", "NX", "depth"};

std::vector<bool> halves(const std::vector<std::string>& specs, std::vector<std::string>* unmatched = nullptr) {
    return halfChannels(kChannels, specs, unmatched);
}

TEST(ExrOptions, SpecsSelectChannelsLayersAndAovsLaterOnesWin) {
    EXPECT_EQ(halves({}), std::vector<bool>(9, false));
    EXPECT_EQ(halves({"half"}), std::vector<bool>(9, true));
    EXPECT_EQ(halves({"aovs=half"}), (std::vector<bool>{false, false, false, false, true, true, true, true, true}));
    // A layer is its name and a dot: N selects N.X, N.Y, N.Z but not NX.
    EXPECT_EQ(halves({"N=half"}), (std::vector<bool>{false, false, false, false, true, true, true, false, false}));
    EXPECT_EQ(halves({"half", "R=float", "G=float", "B=float"}),
              (std::vector<bool>{false, false, false, true, true, true, true, true, true}));
    EXPECT_EQ(halves({"N.Y=half", "float"}), std::vector<bool>(9, false));
}

TEST(ExrOptions, UnmatchedSelectorsAreReported) {
    std::vector<std::string> unmatched;
    halves({"Z=half", "N=half", "P=float"}, &unmatched);
    EXPECT_EQ(unmatched, (std::vector<std::string>{"Z=half", "P=float"}));
}

TEST(ExrOptions, BadSpecsNameThemselves) {
    for (const char* bad : {"quarter", "R=", "=half", "R=double", "", "half=R"}) {
        const std::string e = test::errorOf([&] { checkPixelTypeSpec(bad); });
        EXPECT_EQ(e.rfind(std::string("'") + bad + "': expected half or float", 0), 0u) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
    EXPECT_NO_THROW(checkPixelTypeSpec("N.X=half"));
}

TEST(ExrOptions, PixelTypesText) {
    EXPECT_EQ(pixelTypesText(kChannels, halves({})), "float");
    EXPECT_EQ(pixelTypesText(kChannels, halves({"half"})), "half");
    EXPECT_EQ(pixelTypesText({"R", "G", "N.X"}, {false, false, true}), "R,G float; N.X half");
}

TEST(ExrOptions, TheDefaultIsALosslessCompression) {
    EXPECT_TRUE(exrCompressionIsLossless(kDefaultExrCompression));
    int lossless = 0;
    for (const std::string& n : exrCompressionNames()) lossless += exrCompressionIsLossless(n);
    EXPECT_EQ(lossless, 5);  // none rle zips zip piz
}

}  // namespace
}  // namespace weft
