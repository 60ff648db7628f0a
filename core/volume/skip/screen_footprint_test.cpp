// The footprint is conservative (every ray that crosses a box goes through a
// marked pixel, brute force over whole images with sheared grids) and
// tight (it marks a fraction of the image near the boxes' own), and the
// camera's projection inverts its rays.
#include "core/volume/skip/screen_footprint.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "core/base/rng.hpp"

namespace weft {
namespace {

openvdb::math::Transform::Ptr shearedTransform() {
    return openvdb::math::Transform::createLinearTransform(
        openvdb::math::Mat4d(0.05, 0.01, 0.0, 0.0, 0.0, 0.025, 0.005, 0.0, 0.02, 0.0, 0.07, 0.0, -0.6, -0.4, -0.3, 1.0));
}

Camera lookingAtTheOrigin() {
    Camera c;
    c.eye = Vec3d(0.4, 0.7, 3.0), c.target = Vec3d(0.1, 0.0, 0.0), c.fovY = 35;
    return c;
}

// Whether origin + t dir, t >= 0, meets the box [lo, hi] (slabs), and where.
bool crosses(const Vec3d& origin, const Vec3d& dir, const Vec3d& lo, const Vec3d& hi, double& t0, double& t1) {
    t0 = 0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0) {
            if (origin[a] < lo[a] || origin[a] > hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - origin[a]) / dir[a], tb = (hi[a] - origin[a]) / dir[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
    return t0 <= t1;
}

TEST(CameraRays, ProjectInvertsAt) {
    const CameraRays rays(lookingAtTheOrigin(), 64, 48);
    Rng rng(7);
    for (int i = 0; i < 1000; ++i) {
        const double px = -10 + 84 * rng.uniformDouble(), py = -10 + 68 * rng.uniformDouble(), t = 1e-3 + 100 * rng.uniformDouble();
        const Ray r = rays.at(px, py);
        double qx = 0, qy = 0;
        ASSERT_TRUE(rays.project(r.origin + r.dir * t, qx, qy));
        EXPECT_NEAR(qx, px, 1e-9);
        EXPECT_NEAR(qy, py, 1e-9);
        EXPECT_FALSE(rays.project(r.origin - r.dir * t, qx, qy)) << "behind the eye";
    }
}

TEST(ScreenFootprint, EveryRayThatCrossesABoxIsCovered) {
    const int w = 96, h = 72;
    const CameraRays rays(lookingAtTheOrigin(), w, h);
    const auto xf = shearedTransform();
    ScreenFootprint fp(rays, w, h);
    std::vector<std::pair<Vec3d, Vec3d>> boxes;  // index space
    Rng rng(11);
    for (int i = 0; i < 6; ++i) {
        const Vec3d lo(std::floor(24 * rng.uniform()), std::floor(24 * rng.uniform()), std::floor(24 * rng.uniform()));
        boxes.push_back({lo, lo + Vec3d(0.3 + 2 * rng.uniform(), 0.3 + 2 * rng.uniform(), 0.3 + 2 * rng.uniform())});
        fp.addIndexBox(*xf, boxes.back().first, boxes.back().second);
    }
    int crossing = 0;
    for (int y = 0; y < 4 * h; ++y)
        for (int x = 0; x < 4 * w; ++x) {  // 16 points a pixel, its corners' rows and columns included
            const double px = 0.25 * x, py = 0.25 * y;
            const Ray r = rays.at(px, py);
            const Vec3d o = xf->worldToIndex(r.origin), d = xf->worldToIndex(r.origin + r.dir) - o;
            double from, to;  // where the footprint puts the boxes along the ray
            fp.rayRange(px, py, r.dir, from, to);
            bool any = false;
            for (const auto& [lo, hi] : boxes) {
                double t0, t1;  // world t: d is the world direction mapped, not made unit
                if (!crosses(o, d, lo, hi, t0, t1)) continue;
                any = true;
                ASSERT_TRUE(fp.covers(px, py)) << px << " " << py;
                ASSERT_LE(from, t0) << px << " " << py;
                ASSERT_GE(to, t1) << px << " " << py;
            }
            crossing += any;
        }
    EXPECT_GT(crossing, 100);  // the boxes are in view
    // Tight: the six small boxes' rectangles mark a small part of the image.
    const double covered = fp.coveredFraction();
    EXPECT_GT(covered, double(crossing) / (16.0 * w * h));
    EXPECT_LT(covered, 3.0 * crossing / (16.0 * w * h));
}

TEST(ScreenFootprint, BoxesBehindTheEyeMarkNothingAndOnesAroundItMarkEverything) {
    const CameraRays rays(lookingAtTheOrigin(), 32, 24);
    const auto unit = openvdb::math::Transform::createLinearTransform(1.0);
    ScreenFootprint fp(rays, 32, 24);
    fp.addIndexBox(*unit, Vec3d(-1, -1, 5), Vec3d(1, 1, 7));  // behind: the camera looks down -z from z = 3
    EXPECT_EQ(fp.coveredFraction(), 0.0);
    EXPECT_FALSE(fp.covers(16, 12));
    double t0, t1;
    fp.rayRange(16, 12, rays.at(16, 12).dir, t0, t1);
    EXPECT_GT(t0, t1) << "nothing along the ray";
    EXPECT_TRUE(fp.covers(-0.5, 12)) << "outside the image nothing is known";
    fp.addIndexBox(*unit, Vec3d(-1, -1, 2), Vec3d(1, 1, 4));  // the eye inside
    EXPECT_EQ(fp.coveredFraction(), 1.0);
    EXPECT_TRUE(fp.covers(0.5, 0.5));
}

TEST(ScreenFootprint, ANonLinearMapMarksEverything) {
    const CameraRays rays(lookingAtTheOrigin(), 32, 24);
    const openvdb::BBoxd frustumBox(Vec3d(0), Vec3d(16));
    const auto frustum = openvdb::math::Transform::createFrustumTransform(frustumBox, 0.5, 2.0, 0.1);
    ScreenFootprint fp(rays, 32, 24);
    fp.addIndexBox(*frustum, Vec3d(1), Vec3d(2));
    EXPECT_EQ(fp.coveredFraction(), 1.0);
}

}  // namespace
}  // namespace weft
