// What volume.singlescatter keeps of each volume: the intersector's box
// without the intersector, the intersector built only where a ray marches
// its spans, and the light caches shared between renders of one process.
#include <gtest/gtest.h>

#include "core/volume/grid/octant_shift.hpp"
#include "core/volume/volume.hpp"
#include "plugins/volume_singlescatter/scatter_volume.hpp"
#include "plugins/volume_singlescatter/shared_caches.hpp"
#include "tests/support/render_helpers.hpp"

using namespace weft;

namespace {

const std::string kSmoke = std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb";

}  // namespace

TEST(ScatterVolume, TheBoxWithoutTheIntersectorIsTheIntersectorsBox) {
    initVdb();
    // Voxels on both sides of the origin, a whole active tile, a leaf whose
    // only voxel is switched off again, and a lone voxel far out.
    openvdb::FloatGrid grid(0.0f);
    grid.tree().fill(openvdb::CoordBBox(openvdb::Coord(-256), openvdb::Coord(-129)), 1.0f, true);  // a tile
    for (int i = -20; i <= 20; i += 3) grid.tree().setValue(openvdb::Coord(i, 2 * i, -i), 0.5f);
    grid.tree().setValue(openvdb::Coord(300, 5, 9), 0.25f);
    grid.tree().setValueOff(openvdb::Coord(-300, 400, 40), 0.0f);
    ASSERT_GT(grid.tree().activeTileCount(), 0u);
    const openvdb::Coord shift = -widthBelow(grid.evalActiveVoxelBoundingBox(), 8);
    openvdb::MaskGrid::Ptr mask = shiftedMask(grid.transform(), shift);
    addShiftedTopology(grid.tree(), shift, mask->tree());
    const VdbIntersector intersector(*mask);
    EXPECT_EQ(shiftedNodeBox(grid.tree(), shift), intersector.bbox());
}

TEST(ScatterVolume, TheIntersectorIsBuiltOnlyWhereRaysMarchItsSpans) {
    const Scene scene = loadScene(kSmoke);
    ScatterParams cached;  // still volume, light cache, no emissive triangles: blocks and cache serve every ray
    const std::vector<ScatterVolume> lean = scatterVolumes(scene, cached, false);
    ASSERT_EQ(lean.size(), 1u);
    EXPECT_FALSE(lean[0].intersector);
    EXPECT_TRUE(lean[0].reaching);
    for (const ShadowEstimator traced : {ShadowEstimator::Ratio, ShadowEstimator::Raymarch}) {
        ScatterParams p;
        p.estimator = traced;  // shadow rays march the intersector's spans
        const std::vector<ScatterVolume> full = scatterVolumes(scene, p, false);
        ASSERT_TRUE(full[0].intersector);
        EXPECT_EQ(full[0].occupancyBox, lean[0].occupancyBox);
    }
    ScatterParams lit = cached;
    lit.emitters = true;  // emissive triangles' shadows are traced whatever the estimator
    EXPECT_TRUE(scatterVolumes(scene, lit, false)[0].intersector);
}

// Each render of a frame sequence loads its volume again: an unchanged
// file finds the light cache and blocks the first render built, and the
// image is the one a fresh build gives. Another light or cache setting
// builds its own.
TEST(ScatterVolume, LightCachesAreSharedBetweenRendersOfTheSameVolume) {
    clearScatterCaches();
    const auto lightCaches = [](const RenderOutcome& out) {
        return std::make_pair(out.counters.at("light_cache.built"), out.counters.at("light_cache.reused"));
    };
    const RenderOutcome first = test::render(kSmoke, "40x32", {}, "volume.singlescatter");
    const RenderOutcome second = test::render(kSmoke, "40x32", {}, "volume.singlescatter");
    EXPECT_EQ(lightCaches(first), std::make_pair(std::int64_t(1), std::int64_t(0)));
    EXPECT_EQ(lightCaches(second), std::make_pair(std::int64_t(0), std::int64_t(1)));
    EXPECT_EQ(compareImages(first.image, second.image).overall.maxAbs, 0.0);
    EXPECT_EQ(second.counters.at("light_cache.voxels"), 0);
    const RenderOutcome coarser = test::render(kSmoke, "40x32", {"cache_voxel=3"}, "volume.singlescatter");
    EXPECT_EQ(lightCaches(coarser).first, 1);
    const RenderOutcome otherLight = test::render(kSmoke, "40x32", {"light=0,1,0"}, "volume.singlescatter");
    EXPECT_EQ(lightCaches(otherLight).first, 1);
    clearScatterCaches();
    const RenderOutcome rebuilt = test::render(kSmoke, "40x32", {}, "volume.singlescatter");
    EXPECT_EQ(lightCaches(rebuilt).first, 1);
    EXPECT_EQ(compareImages(first.image, rebuilt.image).overall.maxAbs, 0.0);
}
