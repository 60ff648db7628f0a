// The light cache's voxels: every cache voxel a trilinear lookup of an
// active density voxel can reach, at every coarsening, on both sides of
// the origin (where integer division rounds the other way).
#include <gtest/gtest.h>

#include <openvdb/tools/Morphology.h>

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

TEST(LightCache, HoldsExactlyTheVoxelsLookupsReachAtEveryCoarsening) {
    Volume volume;
    volume.grid = scatteredDensity();
    computeStatistics(volume);
    DirectionalOrPointLight light;
    light.toLight = Vec3d(0.3, 0.8, 0.5).unitSafe();
    light.color = Vec3d(1.0);
    for (const int factor : {1, 2, 3, 4, 5, 6, 7, 8}) {
        SCOPED_TRACE("cache_voxel " + std::to_string(factor));
        const openvdb::FloatGrid::Ptr cache = buildLightCache(volume, volume, light, {1.0, 0.2, 0.005, 0.1, factor});
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

}  // namespace
}  // namespace weft
