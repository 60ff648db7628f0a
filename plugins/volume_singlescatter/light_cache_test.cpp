// The light cache's voxels: every cache voxel a trilinear lookup of an
// active density voxel can reach, at every coarsening, on both sides of
// the origin (where integer division rounds the other way).
#include <gtest/gtest.h>

#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/Morphology.h>

#include <algorithm>

#include <cstdint>

#include "core/base/rng.hpp"
#include "core/volume/volume.hpp"
#include "plugins/volume_singlescatter/light_cache.hpp"

namespace weft {
namespace {

int floorDivision(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Scattered voxels, a solid block and a thin sheet across the origin.
openvdb::FloatGrid::Ptr scatteredDensity() {
    initVdb();
    auto grid = openvdb::FloatGrid::create(0.0f);
    Rng rng(7);
    for (int i = 0; i < 3000; ++i) {
        const std::uint64_t bits = rng.next();
        const openvdb::Coord c(int(bits % 90) - 45, int((bits >> 16) % 70) - 35, int((bits >> 32) % 50) - 25);
        grid->tree().setValue(c, 0.5f);
    }
    grid->tree().fill(openvdb::CoordBBox({3, -9, -17}, {20, 4, -1}), 1.0f, true);
    grid->tree().voxelizeActiveTiles();
    for (int x = -30; x < 30; ++x)
        for (int y = -30; y < 30; ++y) grid->tree().setValue(openvdb::Coord(x, y, 11), 0.25f);
    return grid;
}

// The definition: each active voxel's cache voxel, grown by one in every
// direction (the eight cache voxels around any point of it).
openvdb::MaskTree expectedCacheVoxels(const openvdb::FloatGrid& density, int factor) {
    openvdb::MaskTree mask(false);
    for (auto it = density.cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        mask.setValueOn(openvdb::Coord(floorDivision(c.x(), factor), floorDivision(c.y(), factor), floorDivision(c.z(), factor)));
    }
    openvdb::tools::dilateActiveValues(mask, 1, openvdb::tools::NN_FACE_EDGE_VERTEX, openvdb::tools::IGNORE_TILES);
    return mask;
}

Volume scatteredVolume() {
    Volume volume;
    volume.grid = scatteredDensity();
    computeStatistics(volume);
    return volume;
}

DirectionalOrPointLight slantedLight() {
    DirectionalOrPointLight light;
    light.toLight = Vec3d(0.3, 0.8, 0.5).unitSafe();
    light.color = Vec3d(1.0);
    return light;
}

TEST(LightCache, HoldsExactlyTheVoxelsLookupsReachAtEveryCoarsening) {
    const Volume volume = scatteredVolume();
    const DirectionalOrPointLight light = slantedLight();
    for (const int factor : {1, 2, 3, 4, 5, 6, 7, 8}) {
        SCOPED_TRACE("cache_voxel " + std::to_string(factor));
        const openvdb::FloatGrid::Ptr cache = buildLightCache(volume, volume, nullptr, light, {1.0, 0.2, 0.005, 0.1, factor});
        const openvdb::MaskTree expected = expectedCacheVoxels(*volume.grid, factor);
        EXPECT_EQ(cache->activeVoxelCount(), expected.activeVoxelCount());
        std::int64_t missing = 0;  // the cache places its voxels by its own origin: found by position
        for (auto it = expected.cbeginValueOn(); it; ++it) {
            const Vec3d world = volume.grid->indexToWorld(it.getCoord().asVec3d() * double(factor));
            missing += !cache->tree().isValueOn(openvdb::Coord::round(cache->worldToIndex(world)));
        }
        EXPECT_EQ(missing, 0);
        EXPECT_DOUBLE_EQ(cache->transform().voxelSize()[0], double(factor));
        // Every cache coordinate is positive: the trees stay in one octant.
        const openvdb::CoordBBox box = cache->evalActiveVoxelBoundingBox();
        EXPECT_GE(box.min().x(), 0);
        EXPECT_GE(box.min().y(), 0);
        EXPECT_GE(box.min().z(), 0);
    }
}

// D by its definition, every sample of the march taken (no leaping):
// midpoints (n + 1/2) step from x towards the light until the index box's exit.
double marchedEverywhere(const openvdb::FloatGrid& grid, const openvdb::CoordBBox& box, const Vec3d& x, const Vec3d& dir,
                         double step, double gain, double cutoff) {
    double tExit = 1e300;
    for (int a = 0; a < 3; ++a) {
        if (dir[a] > 1e-12) tExit = std::min(tExit, (box.max()[a] + 0.5 - x[a]) / dir[a]);
        if (dir[a] < -1e-12) tExit = std::min(tExit, (box.min()[a] - 0.5 - x[a]) / dir[a]);
    }
    const openvdb::FloatGrid::ConstAccessor acc = grid.getConstAccessor();
    double D = 0;
    for (double n = 0; (n + 0.5) * step < tExit; ++n) {
        const double t = (n + 0.5) * step, rho = openvdb::tools::BoxSampler::sample(acc, x + dir * t);
        if (rho >= cutoff) D += rho * step / (1.0 + gain * t);
    }
    return D;
}

// The march leaps over space whose lookups stay below the cutoff
// (VisibleBlocks::reaching); D must be what marching every sample gives.
TEST(LightCache, LeapingOverEmptySpaceLeavesEveryPathAsMarchingAllOfIt) {
    const Volume volume = scatteredVolume();
    const DirectionalOrPointLight light = slantedLight();
    const LightCacheSettings settings{0.75, 0.2, 0.3, 0.0, 2};  // cutoff 0.3: the 0.25 sheet is empty space
    const auto reaching = VisibleBlocks::reaching(*volume.grid, 0.3f);
    ASSERT_TRUE(reaching);
    const openvdb::FloatGrid::Ptr cache = buildLightCache(volume, volume, reaching.get(), light, settings);
    int checked = 0, nonZero = 0;
    for (auto it = cache->cbeginValueOn(); it; ++it, ++checked) {
        const Vec3d x = volume.grid->worldToIndex(cache->indexToWorld(it.getCoord()));
        const double expected = marchedEverywhere(*volume.grid, volume.indexBox(), x, light.toLight, 0.75, 0.2, 0.3);
        ASSERT_NEAR(*it, expected, 1e-5 * (1.0 + expected)) << "cache voxel " << it.getCoord();
        nonZero += expected > 0;
    }
    EXPECT_GT(checked, 1000);
    EXPECT_GT(nonZero, checked / 10);
}

}  // namespace
}  // namespace weft
