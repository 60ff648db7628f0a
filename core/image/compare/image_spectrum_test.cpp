// Power spectrum and the coherent-aliasing ratio: a tone is one peak, noise is not.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/image/compare/image_spectrum.hpp"
#include "core/base/rng.hpp"

using namespace weft;

TEST(ImageSpectrum, ParsevalHolds) {
    Rng rng(3);
    std::vector<double> img(24 * 20);
    double energy = 0;
    for (double& v : img) v = rng.uniformDouble() - 0.5, energy += v * v;
    double sum = 0;
    for (double p : powerSpectrum(img, 24, 20)) sum += p;
    EXPECT_NEAR(sum / (24 * 20), energy, 1e-9);
}

TEST(ImageSpectrum, ToneIsOnePeakAtItsFrequency) {
    const int W = 64, H = 48;
    std::vector<double> img(W * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) img[y * W + x] = std::cos(2 * std::numbers::pi * (5.0 * x / W - 7.0 * y / H));
    const AliasingPeak p = coherentAliasing(img, W, H);
    EXPECT_EQ(std::abs(p.fx), 5);
    EXPECT_EQ(std::abs(p.fy), 7);
    EXPECT_EQ(p.fx * p.fy < 0, true);
    EXPECT_GT(p.ratio, 0.4 * W * H);  // two bins hold all the energy
}

TEST(ImageSpectrum, WhiteNoiseHasNoCoherentPeak) {
    const int W = 64, H = 64;
    Rng rng(11);
    std::vector<double> img(W * H);
    for (double& v : img) v = rng.uniformDouble() - 0.5;
    const double r = coherentAliasing(img, W, H).ratio;
    EXPECT_GT(r, 3.0);
    EXPECT_LT(r, 2.5 * std::log(W * H));
}

TEST(ImageSpectrum, BlurKeepsLowFrequenciesAndRemovesFineNoise) {
    const int W = 64, H = 64;
    std::vector<double> flat(W * H, 0.25), checker(W * H), slow(W * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            checker[y * W + x] = (x + y) % 2 ? 0.5 : -0.5;
            slow[y * W + x] = 0.5 * std::sin(2 * std::numbers::pi * x / 64.0);
        }
    EXPECT_NEAR(blurredRms(flat, W, H, 2), 0.25, 1e-12);
    EXPECT_LT(blurredRms(checker, W, H, 2), 0.01);
    EXPECT_GT(blurredRms(slow, W, H, 2), 0.3);
}
