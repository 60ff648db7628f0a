#include <gtest/gtest.h>

#include <cmath>

#include "core/base/error.hpp"
#include "core/image/image_compare.hpp"

using namespace weft;

namespace {

Image constant(int w, int h, float v) {
    Image img = Image::rgba(w, h);
    for (float& x : img.data()) x = v;
    return img;
}

}  // namespace

TEST(ImageCompare, IdenticalImages) {
    const Image a = constant(16, 16, 0.3f);
    const ImageComparison c = compareImages(a, a);
    EXPECT_EQ(c.overall.rmse, 0.0);
    EXPECT_TRUE(std::isinf(c.overall.psnr));
    EXPECT_NEAR(c.overall.ssim, 1.0, 1e-12);
    EXPECT_EQ(c.pixelsAbove, 0);
}

TEST(ImageCompare, KnownOffsetGivesKnownMetrics) {
    const Image a = constant(16, 16, 0.6f), b = constant(16, 16, 0.5f);
    const ImageComparison c = compareImages(a, b);
    EXPECT_NEAR(c.overall.rmse, 0.1, 1e-6);
    EXPECT_NEAR(c.overall.psnr, 20.0, 1e-4);
    EXPECT_NEAR(c.overall.maxAbs, 0.1, 1e-6);
    EXPECT_NEAR(c.overall.relMse, 0.01 / (0.25 + 0.01), 1e-6);
    EXPECT_EQ(c.pixelsAbove, 256);
    // SSIM of constant images reduces to the luminance term.
    const double expected = (2 * 0.6 * 0.5 + 1e-4) / (0.36 + 0.25 + 1e-4);
    EXPECT_NEAR(c.overall.ssim, expected, 1e-5);
}

TEST(ImageCompare, PerChannelAndStructure) {
    Image a = constant(16, 16, 0.5f), b = constant(16, 16, 0.5f);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) a.at(x, y, 1) = ((x + y) % 2) ? 1.0f : 0.0f;  // checker in G only
    const ImageComparison c = compareImages(a, b);
    EXPECT_EQ(c.channels[0].rmse, 0.0);
    EXPECT_NEAR(c.channels[1].rmse, 0.5, 1e-6);
    EXPECT_LT(c.channels[1].ssim, 0.1);  // structure destroyed
    EXPECT_NEAR(c.overall.rmse, std::sqrt(0.25 / 4), 1e-6);
}

TEST(ImageCompare, NonFiniteCountsAsInfiniteErrorAndSizesMustMatch) {
    Image a = constant(8, 8, 0.f);
    a.at(3, 3, 0) = NAN;
    EXPECT_TRUE(std::isinf(compareImages(a, constant(8, 8, 0.f)).overall.maxAbs));
    EXPECT_THROW(compareImages(constant(8, 8, 0.f), constant(8, 9, 0.f)), Error);
}
