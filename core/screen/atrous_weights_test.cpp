// A-Trous tap weights (sample counts): equal weights change nothing, the
// first level pools the samples of its taps exactly, weighting by counts
// lowers the error of unequally sampled pixels to what inverse-variance
// weighting predicts, zero weights are missing samples, bad weights are
// errors.
#include <gtest/gtest.h>

#include <cmath>

#include "core/screen/atrous.hpp"
#include "core/base/error.hpp"
#include "core/base/rng.hpp"

using namespace weft;

namespace {

const GeometryGuides kNoGuides(int w, int h) { return GeometryGuides{w, h, {}, {}}; }

std::vector<float> noise(int w, int h, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<float> c(std::size_t(3) * w * h);
    for (float& v : c) v = rng.uniform();
    return c;
}

// Counts in 3x3 blocks alternating between 1 and 16 samples.
std::vector<float> blockCounts(int w, int h) {
    std::vector<float> n(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) n[std::size_t(y) * w + x] = ((x / 3 + y / 3) % 2) ? 16.0f : 1.0f;
    return n;
}

}  // namespace

TEST(AtrousTapWeights, EqualWeightsChangeNothing) {
    const int w = 31, h = 17;
    const std::vector<float> input = noise(w, h, 1);
    AtrousSettings s;
    s.levels = 4, s.sigmaColor = 0.3f, s.colorDecay = 0.5f;
    std::vector<float> plain = input, weighted = input;
    atrousFilter(plain, w, h, kNoGuides(w, h), s);
    atrousFilter(weighted, w, h, kNoGuides(w, h), s, TapWeights{std::vector<float>(std::size_t(w) * h, 3.0f), 24});
    for (std::size_t i = 0; i < plain.size(); ++i) ASSERT_NEAR(weighted[i], plain[i], 1e-6f) << i;
}

TEST(AtrousTapWeights, FirstLevelPoolsTheSamplesOfItsTaps) {
    // One level, range terms off: pixel p becomes sum h_q n_q c_q / sum h_q n_q,
    // the mean of all its taps' samples with each sample weighted by its tap.
    const int w = 9, h = 8;
    const std::vector<float> input = noise(w, h, 2);
    const std::vector<float> counts = blockCounts(w, h);
    std::vector<float> got = input;
    AtrousSettings s;
    s.levels = 1;
    atrousFilter(got, w, h, kNoGuides(w, h), s, TapWeights{counts, 1});
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0, weight = 0;
                for (int j = -2; j <= 2; ++j)
                    for (int i = -2; i <= 2; ++i) {
                        const int qx = x + i, qy = y + j;
                        if (qx < 0 || qx >= w || qy < 0 || qy >= h) continue;
                        const std::size_t q = std::size_t(qy) * w + qx;
                        const double t = double(kB3Taps[i + 2]) * kB3Taps[j + 2] * counts[q];
                        sum += t * input[3 * q + c], weight += t;
                    }
                ASSERT_NEAR(got[(std::size_t(y) * w + x) * 3 + c], sum / weight, 1e-6) << x << "," << y;
            }
}

TEST(AtrousTapWeights, CountWeightsLowerTheErrorOfUnequallySampledPixels) {
    // Every pixel is the mean of n samples of U(0, 1) (n = 1 or 16 in blocks).
    // After one level the error variance of an interior pixel is
    //   sum h^2 n var / (sum h n)^2 weighted,  sum h^2 var / n / (sum h)^2 plain,
    // with var = 1/12; the measured mean squared errors over the image
    // (fixed seed) must match both within 10% and the weighted one be lower.
    const int w = 192, h = 192;
    const std::vector<float> counts = blockCounts(w, h);
    Rng rng(7);
    std::vector<float> img(std::size_t(3) * w * h);
    for (std::size_t p = 0; p < counts.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            double mean = 0;
            for (int k = 0; k < int(counts[p]); ++k) mean += rng.uniformDouble() / counts[p];
            img[3 * p + c] = float(mean);
        }
    AtrousSettings s;
    s.levels = 1;
    std::vector<float> plain = img, weighted = img;
    atrousFilter(plain, w, h, kNoGuides(w, h), s);
    atrousFilter(weighted, w, h, kNoGuides(w, h), s, TapWeights{counts, 1});
    double msePlain = 0, mseWeighted = 0, expectPlain = 0, expectWeighted = 0, interior = 0;
    for (int y = 2; y < h - 2; ++y)
        for (int x = 2; x < w - 2; ++x) {
            double hn = 0, h2n = 0, h2overN = 0;
            for (int j = -2; j <= 2; ++j)
                for (int i = -2; i <= 2; ++i) {
                    const double t = double(kB3Taps[i + 2]) * kB3Taps[j + 2], n = counts[std::size_t(y + j) * w + x + i];
                    hn += t * n, h2n += t * t * n, h2overN += t * t / n;
                }
            expectWeighted += h2n / (hn * hn) / 12, expectPlain += h2overN / 12;
            for (int c = 0; c < 3; ++c) {
                const std::size_t i = (std::size_t(y) * w + x) * 3 + c;
                msePlain += (plain[i] - 0.5) * (plain[i] - 0.5) / 3, mseWeighted += (weighted[i] - 0.5) * (weighted[i] - 0.5) / 3;
            }
            interior += 1;
        }
    EXPECT_NEAR(msePlain / expectPlain, 1.0, 0.1);
    EXPECT_NEAR(mseWeighted / expectWeighted, 1.0, 0.1);
    EXPECT_LT(mseWeighted, 0.5 * msePlain);
    EXPECT_GT(interior, 0);
}

TEST(AtrousTapWeights, ZeroWeightIsAMissingSampleAndNothingIsNaN) {
    const int w = 12, h = 10;
    std::vector<float> img(std::size_t(3) * w * h, 2.0f);
    for (std::size_t p = 0; p < std::size_t(w) * h; p += 5) img[3 * p] = 1e30f;  // weight 0: never read
    std::vector<float> counts(std::size_t(w) * h, 0.0f);
    counts[std::size_t(5) * w + 6] = 1.0f;  // one pixel carries the image
    AtrousSettings s;
    s.levels = 3;
    atrousFilter(img, w, h, kNoGuides(w, h), s, TapWeights{counts, 1});
    for (float v : img) ASSERT_TRUE(std::isfinite(v));
    EXPECT_FLOAT_EQ(img[(std::size_t(5) * w + 6) * 3 + 1], 2.0f);
    EXPECT_FLOAT_EQ(img[(std::size_t(6) * w + 7) * 3 + 1], 2.0f);  // filled from it at level 0
}

TEST(AtrousTapWeights, RejectsNegativeNonFiniteOrMissizedWeights) {
    const int w = 4, h = 4;
    std::vector<float> img(std::size_t(3) * w * h, 1.0f);
    const AtrousSettings s;
    for (float bad : {-1.0f, std::nanf(""), INFINITY}) {
        std::vector<float> counts(std::size_t(w) * h, 1.0f);
        counts[3] = bad;
        EXPECT_THROW(atrousFilter(img, w, h, kNoGuides(w, h), s, TapWeights{counts, 1}), Error) << bad;
    }
    EXPECT_THROW(atrousFilter(img, w, h, kNoGuides(w, h), s, TapWeights{std::vector<float>(5, 1.0f), 1}), Error);
}
