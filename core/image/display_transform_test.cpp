// The display transform's 8-bit encoding (built-in config: the sRGB curve)
// against the IEC 61966-2-1 formula: within one step of 255 everywhere and
// exact almost everywhere (the pixels reach OpenColorIO as half floats);
// NaN, Inf, negative and huge values stay in range; the bytes of a pixel
// do not depend on which run of pixels it is encoded with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include "core/image/color.hpp"

namespace weft {
namespace {

int srgbByte(double linear) {
    const double v = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
    return int(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

TEST(DisplayTransform, EncodesTheSrgbCurveToEightBits) {
    if (std::getenv("OCIO")) GTEST_SKIP() << "$OCIO names a studio config; the built-in one is checked";
    const int n = 20000;
    std::vector<float> rgb(3 * n);
    for (int i = 0; i < 3 * n; ++i) rgb[i] = float(std::pow(double(i) / (3 * n - 1), 2.2));  // dense near black
    std::vector<unsigned char> out(3 * n);
    displayTransform().encode8(rgb.data(), out.data(), n);
    int exact = 0;
    for (int i = 0; i < 3 * n; ++i) {
        const int want = srgbByte(rgb[i]);
        ASSERT_LE(std::abs(int(out[i]) - want), 1) << "linear " << rgb[i];
        exact += out[i] == want;
    }
    EXPECT_GE(exact, 0.97 * 3 * n);
}

TEST(DisplayTransform, OutOfRangeValuesStayInRange) {
    if (std::getenv("OCIO")) GTEST_SKIP() << "$OCIO names a studio config; the built-in one is checked";
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<float> rgb = {std::nanf(""), inf, -inf, -1.0f, 1e30f, 70000.0f, 1e-30f, 0.0f, 1.0f};
    std::vector<unsigned char> out(rgb.size());
    displayTransform().encode8(rgb.data(), out.data(), int(rgb.size() / 3));
    const std::vector<unsigned char> want = {0, 0, 0, 0, 255, 255, 0, 0, 255};
    EXPECT_EQ(out, want);
}

TEST(DisplayTransform, APixelEncodesTheSameInAnyRun) {
    const int n = 999;
    std::vector<float> rgb(3 * n);
    for (int i = 0; i < 3 * n; ++i) rgb[i] = float(std::fmod(i * 0.377, 1.7));
    std::vector<unsigned char> whole(3 * n), pieces(3 * n);
    displayTransform().encode8(rgb.data(), whole.data(), n);
    for (int start = 0, len = 1; start < n; start += len, len = len % 7 + 1)
        displayTransform().encode8(&rgb[3 * start], &pieces[3 * start], std::min(len, n - start));
    EXPECT_EQ(whole, pieces);
}

}  // namespace
}  // namespace weft
