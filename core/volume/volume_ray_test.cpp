// Segment opacity within 2 ulp of 1 - exp(-t) over float's range, and
// camera rays in a volume's index space: the directions mapped through the
// transform's linear part are the map's own differences.
#include "core/volume/volume_ray.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tests/support/volume_fixtures.hpp"

namespace weft {
namespace {

// Every float depth from 1e-30 to 100 in steps of a factor 1.0001 (about
// 737,000 values, both sides of every change of k in the range reduction):
// within 2 ulp of the double-precision -expm1(-t), in [0, 1] and never
// decreasing; 0 at 0, 1 from 87 on and at infinity, NaN for NaN.
TEST(OpacityOfDepth, WithinTwoUlpOfExpm1AndMonotonic) {
    double worstUlps = 0;
    float previous = 0;
    for (double t = 1e-30; t < 100; t *= 1.0001) {
        const float depth = float(t), got = opacityOfDepth(depth);
        const float want = float(-std::expm1(-double(depth)));
        const double ulp = double(std::nextafter(want, 2.0f)) - double(want);
        worstUlps = std::max(worstUlps, std::abs(double(got) - -std::expm1(-double(depth))) / ulp);
        ASSERT_GE(got, previous) << "t " << depth;
        ASSERT_LE(got, 1.0f) << "t " << depth;
        previous = got;
    }
    EXPECT_LE(worstUlps, 2.0);
    EXPECT_EQ(opacityOfDepth(0.0f), 0.0f);
    EXPECT_FALSE(std::signbit(opacityOfDepth(0.0f)));
    EXPECT_EQ(opacityOfDepth(87.0f), 1.0f);
    EXPECT_EQ(opacityOfDepth(std::numeric_limits<float>::max()), 1.0f);
    EXPECT_EQ(opacityOfDepth(std::numeric_limits<float>::infinity()), 1.0f);
    EXPECT_TRUE(std::isnan(opacityOfDepth(std::numeric_limits<float>::quiet_NaN())));
    EXPECT_EQ(opacityOfDepth(std::numeric_limits<float>::denorm_min()), std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(segmentOpacity(-5.0f, 2.0f), 0.0f);  // negative extinction: clear
    EXPECT_EQ(segmentOpacity(1e30f, 1e30f), 1.0f);  // a product beyond float: opaque
}

TEST(IndexDirections, AreTheMapsDifferencesOfWorldPoints) {
    const Volume v = test::skewedVolume();
    const IndexDirections toIndex(v);
    const auto& xf = v.grid->transform();
    const Vec3d origin(0.3, -1.2, 4.0);
    for (const Vec3d d : {Vec3d(1, 0, 0), Vec3d(0, -1, 0), Vec3d(0.2, 0.7, -0.4), Vec3d(1e-9, 3e8, -2.5)}) {
        const Vec3d expected = xf.worldToIndex(origin + d) - xf.worldToIndex(origin);
        const Vec3d got = toIndex(d);
        EXPECT_NEAR((got - expected).length(), 0.0, 1e-9 * (1 + expected.length())) << d;
    }
}

}  // namespace
}  // namespace weft
