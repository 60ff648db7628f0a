// Transmittance estimators against closed forms: ratio tracking is
// unbiased (t-test over fixed seeds), the fixed-step march converges at
// first order, and extremes stay finite.
#include <gtest/gtest.h>

#include <cmath>

#include "core/volume/media/transmittance.hpp"

using namespace weft;

namespace {

struct Moments {
    double mean = 0, sd = 0;
};

template <class Sigma>
Moments ratioTrackingMoments(const Sigma& sigma, double length, double majorant, int n, std::uint64_t seed) {
    Rng rng(seed);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        const double T = ratioTracking(sigma, 0.0, length, majorant, rng)[1];
        sum += T, sum2 += T * T;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean))};
}

}  // namespace

TEST(RatioTracking, UnbiasedInAHomogeneousSlab) {
    auto sigma = [](double) { return Vec3d(0.7); };
    for (double majorant : {0.7, 1.5, 6.0}) {
        const Moments m = ratioTrackingMoments(sigma, 2.0, majorant, 20000, 11);
        const double exact = std::exp(-1.4);
        EXPECT_LT(std::abs(m.mean - exact), 4.0 * m.sd / std::sqrt(20000.0) + 1e-12) << majorant;
    }
}

TEST(RatioTracking, UnbiasedInALinearRamp) {
    const double a = 0.2, b = 0.9, length = 3.0;  // sigma(t) = a + b t
    auto sigma = [&](double t) { return Vec3d(a + b * t); };
    const Moments m = ratioTrackingMoments(sigma, length, a + b * length, 20000, 12);
    const double exact = std::exp(-(a * length + 0.5 * b * length * length));
    EXPECT_LT(std::abs(m.mean - exact), 4.0 * m.sd / std::sqrt(20000.0));
    EXPECT_GT(m.sd, 0.0);  // an estimator, not the closed form
}

TEST(RatioTracking, ChannelsAreTrackedSeparately) {
    auto sigma = [](double) { return Vec3d(0.1, 0.5, 1.0); };
    Rng rng(3);
    Vec3d sum(0.0);
    const int n = 20000;
    for (int i = 0; i < n; ++i) sum += ratioTracking(sigma, 0.0, 1.0, 1.0, rng);
    EXPECT_NEAR(sum[0] / n, std::exp(-0.1), 0.01);
    EXPECT_NEAR(sum[1] / n, std::exp(-0.5), 0.01);
    EXPECT_NEAR(sum[2] / n, std::exp(-1.0), 0.01);  // majorant equals sigma: only paths without a collision count
}

TEST(MarchTransmittance, ConvergesAtFirstOrderOnARamp) {
    const double a = 0.2, b = 0.9, length = 3.0;
    auto sigma = [&](double t) { return Vec3d(a + b * t); };
    const double exact = std::exp(-(a * length + 0.5 * b * length * length));
    auto error = [&](double h) { return std::abs(marchTransmittance(sigma, 1e-9, length, h, 0.0)[0] - exact); };
    const double coarse = error(0.2), fine = error(0.025);  // 8x finer
    EXPECT_GT(coarse / fine, 5.0);
    EXPECT_LT(coarse / fine, 12.0);
    EXPECT_LT(fine, 0.01);
}

TEST(Transmittance, ExtremesStayFiniteAndInRange) {
    Rng rng(5);
    auto huge = [](double) { return Vec3d(1e30); };
    auto zero = [](double) { return Vec3d(0.0); };
    for (const Vec3d& T : {ratioTracking(huge, 0, 1, 1e30, rng), ratioTracking(zero, 0, 1, 0, rng),
                           ratioTracking(zero, 0, 1e30, 1e-30, rng), marchTransmittance(huge, 0, 1, 1e-3, 0.005),
                           marchTransmittance(zero, 0, 1e6, 1.0, 0.0), marchTransmittance(huge, 0, 1, 1e-3, 0.0)})
        for (int c = 0; c < 3; ++c) {
            EXPECT_TRUE(std::isfinite(T[c]));
            EXPECT_GE(T[c], 0.0);
            EXPECT_LE(T[c], 1.0);
        }
}
