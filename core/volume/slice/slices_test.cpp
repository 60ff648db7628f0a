// The pyramid's rays (makeLevelRays), built from the directions mapped
// through the transform's linear part, cross the same slices as camera rays
// mapped into the volume's index space one by one (sliceRayOf).
#include "core/volume/slice/slices.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "tests/support/volume_fixtures.hpp"

namespace weft {
namespace {

TEST(MakeLevelRays, CrossTheSlicesOfRaysMappedOneByOne) {
    const Volume v = test::skewedVolume();
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
