// Analytic scenes: exact pixel integrals against dense quadrature, and the
// moving disc's time coverage against its closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "core/sampling/analytic2d.hpp"
#include "core/base/error.hpp"

using namespace weft;

namespace {

// n x n midpoints in the pixel (and the whole shutter for the disc).
double dense(const AnalyticImage& img, AnalyticScene scene, int px, int py, int n) {
    double s = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double x = px + (i + 0.5) / n, y = py + (j + 0.5) / n;
            s += scene == AnalyticScene::Disc ? img.timeCoverage(x, y) : img.value(x, y, 0.5);
        }
    return s / (n * n);
}

}  // namespace

TEST(Analytic2D, ExactPixelIntegralsAgreeWithDenseQuadrature) {
    const int W = 40, H = 32;
    for (const char* name : {"zoneplate", "grating", "checker", "siemens", "lines", "disc"}) {
        const AnalyticScene scene = analyticSceneFromName(name);
        const AnalyticImage img(scene, W, H);
        double worst = 0, sum = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const double d = std::abs(img.pixelIntegral(x, y) - dense(img, scene, x, y, 128));
                worst = std::max(worst, d), sum += d;
            }
        // Midpoints on a 128^2 grid err by at most a few cells' area along an edge.
        EXPECT_LT(worst, 0.03) << name;
        EXPECT_LT(sum / (W * H), 1e-3) << name;
    }
}

TEST(Analytic2D, SmoothScenesAreExactToQuadratureAccuracy) {
    for (const char* name : {"zoneplate", "grating"}) {
        const AnalyticScene scene = analyticSceneFromName(name);
        const AnalyticImage img(scene, 24, 24);
        for (int y = 0; y < 24; y += 5)
            for (int x = 0; x < 24; x += 3) EXPECT_NEAR(img.pixelIntegral(x, y), dense(img, scene, x, y, 256), 2e-5) << name;
    }
}

TEST(Analytic2D, ValuesAndIntegralsStayInTheUnitInterval) {
    for (const char* name : {"zoneplate", "grating", "checker", "siemens", "lines", "disc"}) {
        const AnalyticImage img(analyticSceneFromName(name), 33, 17);
        for (int y = 0; y < 17; ++y)
            for (int x = 0; x < 33; ++x) {
                const double v = img.pixelIntegral(x, y);
                EXPECT_TRUE(v >= -1e-12 && v <= 1 + 1e-12) << name << " " << v;
            }
    }
}

TEST(Analytic2D, MovingDiscCoverageConvergesToTheClosedForm) {
    // Stratified time samples of an interval indicator err by at most 2/N.
    const AnalyticImage img(AnalyticScene::Disc, 256, 256);
    for (auto [x, y] : {std::pair{70.3, 128.2}, {128.0, 100.0}, {200.5, 150.7}, {40.0, 128.0}, {128.0, 171.0}})
        for (int n : {16, 256, 4096}) {
            double s = 0;
            for (int k = 0; k < n; ++k) s += img.value(x, y, (k + 0.5) / n);
            EXPECT_NEAR(s / n, img.timeCoverage(x, y), 2.0 / n) << x << "," << y << " n=" << n;
        }
    EXPECT_EQ(img.timeCoverage(128, 10), 0.0);                  // never reached
    EXPECT_NEAR(img.timeCoverage(128, 128), 2 * (256 / 6.0) / 128, 1e-12);  // the diameter over the travel
}

TEST(Analytic2D, UnknownSceneIsAnError) { EXPECT_THROW(analyticSceneFromName("mandrill"), Error); }
