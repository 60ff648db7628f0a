// The marched transmittance against closed forms: a homogeneous box is
// exact, the one-voxel trilinear ramp at a face integrates to half a voxel,
// empty bricks cost no step, and finer steps converge on a heterogeneous grid.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/volume/media/marched_transmittance.hpp"
#include "tests/support/volume_fixtures.hpp"

using namespace weft;
using weft::test::cubeVolume;

TEST(MarchedTransmittance, HomogeneousInteriorIsExact) {
    const Vec3d absorb(0.01, 0.02, 0.05), scatter(0.02, 0.04, 0.05);
    const std::vector<Volume> volumes{cubeVolume(16, absorb, scatter, [](int, int, int) { return 1.0f; })};
    const Medium medium(volumes);  // keeps pointers into volumes
    MediumRay ray(medium);
    for (double step : {0.3, 1.0, 4.0}) {
        ray.reset(Vec3d(0.2, 0.5, 0.5), Vec3d(1, 0, 0), 0.6);
        std::int64_t steps = 0;
        const Vec3d T = marchedTransmittance(ray, step, steps);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(T[c], std::exp(-16.0 * (absorb[c] + scatter[c]) * 0.6), 1e-12) << step;
        EXPECT_GE(steps, std::int64_t(std::ceil(0.6 * 16 / step))) << step;
    }
}

TEST(MarchedTransmittance, ACrossingIntegratesTheFacesRampsToHalfAVoxelEach) {
    // Through the whole cube along x: 16 voxels of density 1 plus two ramps
    // of one voxel each (half a voxel of density each): 16 voxels in all.
    const Vec3d absorb(0.05), scatter(0.0);
    const std::vector<Volume> volumes{cubeVolume(16, absorb, scatter, [](int, int, int) { return 1.0f; })};
    const Medium medium(volumes);  // keeps pointers into volumes
    MediumRay ray(medium);
    ray.reset(Vec3d(-1, 0.5, 0.5), Vec3d(1, 0, 0), 10);
    std::int64_t steps = 0;
    EXPECT_NEAR(marchedTransmittance(ray, 1.0, steps)[0], std::exp(-0.05 * 16), 1e-12);
}

TEST(MarchedTransmittance, EmptyBricksTakeNoStep) {
    // Density only in the first 4 voxels along x; a ray along y at x = 0.9
    // (voxel 28.8, brick 3; the bound spreads to brick 1 only) crosses
    // bricks whose majorant is 0.
    const std::vector<Volume> volumes{cubeVolume(32, Vec3d(0.1), Vec3d(0.1), [](int i, int, int) { return i < 4 ? 1.0f : 0.0f; })};
    const Medium medium(volumes);  // keeps pointers into volumes
    MediumRay ray(medium);
    ray.reset(Vec3d(0.9, -1, 0.5), Vec3d(0, 1, 0), 10);
    std::int64_t steps = 0;
    EXPECT_EQ(marchedTransmittance(ray, 0.5, steps), Vec3d(1.0));
    EXPECT_EQ(steps, 0);
    EXPECT_EQ(ray.lookups, 0);
}

TEST(MarchedTransmittance, ConvergesOnAHeterogeneousGrid) {
    const std::vector<Volume> volumes{cubeVolume(16, Vec3d(0.2), Vec3d(0.1), [](int i, int j, int k) {
        return float(0.5 + 0.5 * std::sin(0.9 * i + 0.4 * j) * std::cos(0.7 * k));
    })};
    const Medium medium(volumes);  // keeps pointers into volumes
    MediumRay ray(medium);
    auto march = [&](double step) {
        ray.reset(Vec3d(0.03, 0.11, 0.07), Vec3d(0.8, 0.48, 0.36), 10);
        std::int64_t steps = 0;
        return marchedTransmittance(ray, step, steps)[0];
    };
    const double fine = march(0.01);
    EXPECT_GT(fine, 0.01);
    EXPECT_LT(fine, 0.9);
    EXPECT_NEAR(march(0.5), fine, 2e-3 * fine);
    EXPECT_LT(std::abs(march(0.25) - fine), std::abs(march(2.0) - fine) + 1e-12);
}
