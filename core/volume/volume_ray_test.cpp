// Segment opacity within 2 ulp of 1 - exp(-t) over float's range, and
// camera rays in a volume's index space: the directions mapped through the
// transform's linear part are the map's own differences, and the pyramid's
// rays built from them cross the same slices as rays mapped one by one.
#include "core/volume/volume_ray.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/volume/slices.hpp"

namespace weft {
namespace {

// Sheared, anisotropic and moved away from the origin, with data in one corner.
Volume skewedVolume() {
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(
        openvdb::math::Mat4d(0.5, 0.1, 0.0, 0.0, 0.0, 0.25, 0.05, 0.0, 0.2, 0.0, 0.7, 0.0, 1.0, -2.0, 3.0, 1.0)));
    grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(-5, 2, 0), openvdb::Coord(20, 17, 11)), 1.0f, true);
    grid->tree().voxelizeActiveTiles();
    Volume v;
    v.grid = grid;
    computeStatistics(v);
    return v;
}

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
    const Volume v = skewedVolume();
    const IndexDirections toIndex(v);
    const auto& xf = v.grid->transform();
    const Vec3d origin(0.3, -1.2, 4.0);
    for (const Vec3d d : {Vec3d(1, 0, 0), Vec3d(0, -1, 0), Vec3d(0.2, 0.7, -0.4), Vec3d(1e-9, 3e8, -2.5)}) {
        const Vec3d expected = xf.worldToIndex(origin + d) - xf.worldToIndex(origin);
        const Vec3d got = toIndex(d);
        EXPECT_NEAR((got - expected).length(), 0.0, 1e-9 * (1 + expected.length())) << d;
    }
}

TEST(MakeLevelRays, CrossTheSlicesOfRaysMappedOneByOne) {
    const Volume v = skewedVolume();
    Camera camera;
    camera.eye = Vec3d(4, 1, 12), camera.target = Vec3d(3, 1, 3), camera.fovY = 50;
    const SliceSetup slices = makeSliceSetup(camera, v, 0.5, 2);
    const int w = 48, h = 40;
    int inside = 0;
    for (int level = 0; level <= 2; ++level) {
        const LevelRays rays = makeLevelRays(camera, v, slices, level, w, h, w, h);
        const CameraRays eye(camera, w, h);
        for (int y = 0; y < rays.height; ++y)
            for (int x = 0; x < rays.width; ++x) {
                const int i = rays.index(x, y), scale = 1 << level;
                const SliceRay one = sliceRayOf(eye.at(scale * (x + 0.5), scale * (y + 0.5)), v, slices);
                EXPECT_NEAR((rays.dir[i] - one.dir).length(), 0.0, 1e-12);
                int first = 1, last = 0;
                if (one.inside) {
                    const auto [f, l] = one.slices(slices);
                    first = std::max(0, f), last = std::min(slices.imax, l);
                }
                EXPECT_EQ(rays.first[i], first) << level << " " << x << " " << y;
                EXPECT_EQ(rays.last[i], last) << level << " " << x << " " << y;
                inside += first <= last;
            }
    }
    EXPECT_GT(inside, 500);  // the volume fills part of the frame, not none of it
}

}  // namespace
}  // namespace weft
