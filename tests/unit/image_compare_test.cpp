#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/base/error.hpp"
#include "core/image/compare/image_compare.hpp"

#include <tbb/task_arena.h>

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

namespace {

// SSIM as its definition reads: each 8x8 window (stride 4; as wide or as
// tall as the image where it is smaller) summed twice, in long double.
double directSsim(const Image& a, const Image& b, int c) {
    const long double C1 = 0.01L * 0.01L, C2 = 0.03L * 0.03L;
    const int ww = std::min(8, a.width()), wh = std::min(8, a.height());
    const long double n = ww * wh, dof = n > 1 ? n - 1 : 1;
    long double sum = 0;
    int windows = 0;
    for (int y0 = 0; y0 + wh <= a.height(); y0 += 4)
        for (int x0 = 0; x0 + ww <= a.width(); x0 += 4, ++windows) {
            long double ma = 0, mb = 0, vaa = 0, vbb = 0, vab = 0;
            for (int y = y0; y < y0 + wh; ++y)
                for (int x = x0; x < x0 + ww; ++x) ma += a.at(x, y, c), mb += b.at(x, y, c);
            ma /= n, mb /= n;
            for (int y = y0; y < y0 + wh; ++y)
                for (int x = x0; x < x0 + ww; ++x) {
                    const long double da = a.at(x, y, c) - ma, db = b.at(x, y, c) - mb;
                    vaa += da * da, vbb += db * db, vab += da * db;
                }
            vaa /= dof, vbb /= dof, vab /= dof;
            sum += ((2 * ma * mb + C1) * (2 * vab + C2)) / ((ma * ma + mb * mb + C1) * (vaa + vbb + C2));
        }
    return double(sum / windows);
}

// Values around `offset` with noise of `spread`; the second image adds its own noise.
std::pair<Image, Image> noisyPair(float offset, float spread, int w = 37, int h = 29) {
    Image a = Image::rgba(w, h), b = Image::rgba(w, h);
    for (std::size_t i = 0; i < a.data().size(); ++i) {
        const float u = float((i * 2654435761u) % 1000) / 1000, v = float((i * 40503u + 7) % 997) / 997;
        a.data()[i] = offset + spread * u;
        b.data()[i] = offset + spread * (0.7f * u + 0.3f * v);
    }
    return {a, b};
}

}  // namespace

// The windows' moments are joined from 4x4 blocks; SSIM stays the
// definition's, also where values of 1e6 differ by 1e-1 (HDR highlights),
// where sums of squares would lose every digit, and on images narrower or
// shorter than a window.
TEST(ImageCompare, SsimMatchesItsDefinitionAtAnyOffset) {
    for (const auto& [offset, spread] : {std::pair{0.0f, 1.0f}, std::pair{0.5f, 1e-3f}, std::pair{1e6f, 0.1f}, std::pair{-3e4f, 50.0f}}) {
        const auto pair = noisyPair(offset, spread);
        const Image& a = pair.first;  // named references, not bindings: lambdas below capture them
        const Image& b = pair.second;
        const ImageComparison c = compareImages(a, b);
        for (int ch = 0; ch < 4; ++ch)
            EXPECT_NEAR(c.channels[ch].ssim, directSsim(a, b, ch), 1e-9) << "offset " << offset << " channel " << ch;
        ImageComparison one, four;  // rows are summed alone, then in order: any thread count gives the same figures
        tbb::task_arena(1).execute([&] { one = compareImages(a, b); });
        tbb::task_arena(4).execute([&] { four = compareImages(a, b); });
        for (const ImageComparison* r : {&one, &four}) {
            EXPECT_EQ(r->overall.ssim, c.overall.ssim);
            EXPECT_EQ(r->overall.rmse, c.overall.rmse);
            EXPECT_EQ(r->overall.relMse, c.overall.relMse);
        }
    }
    for (const auto& [w, h] : {std::pair{5, 29}, std::pair{37, 6}, std::pair{3, 2}, std::pair{8, 8}, std::pair{12, 9}}) {
        const auto [a, b] = noisyPair(0.25f, 0.5f, w, h);
        const ImageComparison c = compareImages(a, b);
        for (int ch = 0; ch < 4; ++ch) EXPECT_NEAR(c.channels[ch].ssim, directSsim(a, b, ch), 1e-9) << w << "x" << h << " channel " << ch;
    }
}
