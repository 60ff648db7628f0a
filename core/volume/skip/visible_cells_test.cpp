// visibleCells marks every cell in which a trilinear lookup can have a
// non-zero extinction through the transfer function's table, so a march
// that skips the others changes nothing; and it marks few enough to pay.
#include "core/volume/skip/visible_cells.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/volume/grid/leaf_sampler.hpp"
#include "core/volume/volume.hpp"

namespace weft {
namespace {

// Transparent at 0 (the background) and at 1, visible only in between:
// interpolating a 1 with the background passes through the visible band.
TransferFunction band() {
    return TransferFunction(0, 1, {{0, {1, 1, 1}, 0}, {0.3, {1, 1, 1}, 0}, {0.45, {1, 1, 1}, 2}, {0.55, {1, 1, 1}, 2},
                                   {0.7, {1, 1, 1}, 0}, {1, {1, 1, 1}, 0}});
}

bool marked(const openvdb::FloatGrid& cells, int x, int y, int z) { return cells.tree().isValueOn(openvdb::Coord(x, y, z)); }

TEST(TransferFunction, TransparentOverIsExactlyWhereEveryLookupHasZeroExtinction) {
    const TransferFunction tf = band();
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> value(-0.2f, 1.2f);
    int transparent = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        float lo = value(rng), hi = value(rng);
        if (lo > hi) std::swap(lo, hi);
        if (!tf.transparentOver(lo, hi)) continue;
        ++transparent;
        for (int k = 0; k <= 64; ++k) ASSERT_EQ(tf.lookup(lo + (hi - lo) * float(k) / 64).extinction, 0.0f) << lo << " " << hi;
    }
    EXPECT_GT(transparent, 300);  // the band's outer ranges are found transparent, not only refused
    EXPECT_TRUE(tf.transparentOver(0.0f, 0.25f));
    EXPECT_TRUE(tf.transparentOver(0.75f, 5.0f));
    EXPECT_FALSE(tf.transparentOver(0.0f, 1.0f));  // spans the band though both ends are transparent
    EXPECT_FALSE(tf.transparentOver(0.5f, 0.5f));
    const TransferFunction ramp(0, 1, {{0, {1, 1, 1}, 0}, {1, {1, 1, 1}, 1}});  // zero at 0 alone
    EXPECT_TRUE(ramp.transparentOver(0.0f, 0.0f));
    EXPECT_FALSE(ramp.transparentOver(0.0f, 1e-3f));
    EXPECT_FALSE(tf.transparentOver(0.0f, std::numeric_limits<float>::quiet_NaN()));
    EXPECT_FALSE(tf.transparentOver(0.0f, std::numeric_limits<float>::infinity()));
}

TEST(VisibleCells, AValueTheFunctionHidesIsVisibleWhereItsRangeWithTheBackgroundIsNot) {
    initVdb();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->tree().setValue(openvdb::Coord(3, 3, 3), 1.0f);  // transparent itself
    const openvdb::FloatGrid::Ptr cells = visibleCells(*grid, band());
    ASSERT_TRUE(cells);
    // The eight cells with (3, 3, 3) as a corner interpolate 0..1: visible.
    for (int x = 2; x <= 3; ++x)
        for (int y = 2; y <= 3; ++y)
            for (int z = 2; z <= 3; ++z) EXPECT_TRUE(marked(*cells, x, y, z)) << x << y << z;
    EXPECT_EQ(cells->tree().activeVoxelCount(), 8u);

    // A block of 1s: its inner cells interpolate 1s only and stay unmarked.
    grid->tree().fill(openvdb::CoordBBox({16, 16, 16}, {23, 23, 23}), 1.0f, true);
    grid->tree().voxelizeActiveTiles();
    const openvdb::FloatGrid::Ptr blockCells = visibleCells(*grid, band());
    EXPECT_FALSE(marked(*blockCells, 19, 19, 19));
    EXPECT_TRUE(marked(*blockCells, 15, 19, 19));  // straddles the background below the block
    EXPECT_TRUE(marked(*blockCells, 23, 19, 19));  // and above it
    // The cells with a low corner in [15, 23]^3 but not in the all-1 [16, 22]^3, and the first eight.
    EXPECT_EQ(blockCells->tree().activeVoxelCount(), 8u + (9 * 9 * 9 - 7 * 7 * 7));
}

TEST(VisibleCells, InactiveValuesAndTilesCountByTheirValues) {
    initVdb();
    const TransferFunction ramp(0, 1, {{0, {1, 1, 1}, 0}, {0.5, {1, 1, 1}, 0}, {1, {1, 1, 1}, 1}});
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->tree().setValue(openvdb::Coord(0, 0, 0), 0.2f);         // active, transparent
    grid->tree().setValueOff(openvdb::Coord(40, 0, 0), 0.9f);     // inactive, visible
    grid->tree().addTile(1, openvdb::Coord(128, 0, 0), 0.9f, false);  // an inactive visible 8^3 tile
    const openvdb::FloatGrid::Ptr cells = visibleCells(*grid, ramp);
    EXPECT_FALSE(marked(*cells, 0, 0, 0));
    EXPECT_FALSE(marked(*cells, -1, -1, -1));
    EXPECT_TRUE(marked(*cells, 40, 0, 0));
    EXPECT_TRUE(marked(*cells, 39, -1, -1));
    EXPECT_TRUE(marked(*cells, 131, 3, 3));
    EXPECT_TRUE(marked(*cells, 127, 0, 0));  // straddles into the tile from below
    EXPECT_FALSE(marked(*cells, 140, 0, 0));

    const TransferFunction fog(0, 1, {{0, {1, 1, 1}, 0.1}});
    EXPECT_FALSE(visibleCells(*grid, fog));  // a visible background: nothing may be skipped
}

// The property a skipping march relies on, on noise with NaN and infinite
// voxels: a lookup in an unmarked cell has exactly zero extinction.
TEST(VisibleCells, EveryLookupOutsideTheMarkedCellsIsTransparent) {
    initVdb();
    auto grid = openvdb::FloatGrid::create(0.0f);
    auto acc = grid->getAccessor();
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> value(-0.5f, 1.5f);
    for (int x = -12; x < 20; ++x)
        for (int y = -12; y < 20; ++y)
            for (int z = -12; z < 20; ++z)
                if ((x + 2 * y + 3 * z) % 7 != 0) acc.setValue(openvdb::Coord(x, y, z), value(rng));
    acc.setValue(openvdb::Coord(5, 5, 5), std::numeric_limits<float>::quiet_NaN());
    acc.setValue(openvdb::Coord(-5, 5, 5), std::numeric_limits<float>::infinity());
    const TransferFunction tf = band();
    const openvdb::FloatGrid::Ptr cells = visibleCells(*grid, tf);
    ASSERT_TRUE(cells);
    const openvdb::FloatGrid::ConstAccessor read = grid->getConstAccessor();
    LeafSampler sampler(read, grid->transform());
    std::uniform_real_distribution<double> at(-14.0, 22.0);
    int skipped = 0, visible = 0;
    for (int trial = 0; trial < 200000; ++trial) {
        const openvdb::Vec3d p(at(rng), at(rng), at(rng));
        const float extinction = tf.lookup(sampler.isSample(p)).extinction;
        if (marked(*cells, int(std::floor(p.x())), int(std::floor(p.y())), int(std::floor(p.z())))) {
            visible += extinction != 0.0f;
            continue;
        }
        ++skipped;
        ASSERT_EQ(extinction, 0.0f) << p;
    }
    EXPECT_GT(skipped, 40000);  // the band hides much of the noise: skipping pays
    EXPECT_GT(visible, 10000);
    EXPECT_TRUE(marked(*cells, 5, 5, 5));
    EXPECT_TRUE(marked(*cells, 4, 4, 4));
}

// The march's per-sample test reads the marked cells' leaf masks and tile
// states; it must agree with the grid at every point, negative ones and
// points inside a whole visible tile included.
TEST(VisibleCells, TheCellTestAgreesWithTheMarkedGridEverywhere) {
    initVdb();
    const TransferFunction ramp(0, 1, {{0, {1, 1, 1}, 0}, {0.5, {1, 1, 1}, 0}, {1, {1, 1, 1}, 1}});
    auto grid = openvdb::FloatGrid::create(0.0f);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    for (int x = -20; x < 12; ++x)
        for (int y = -9; y < 9; ++y)
            for (int z = -9; z < 9; ++z) grid->tree().setValue(openvdb::Coord(x, y, z), value(rng));
    grid->tree().addTile(2, openvdb::Coord(128, 0, 0), 0.9f, true);  // a visible 128^3 tile
    const openvdb::FloatGrid::Ptr cells = visibleCells(*grid, ramp);
    ASSERT_TRUE(cells);
    int tileVoxels = 0;
    for (auto tile = cells->tree().cbeginValueOn(); tile; ++tile) tileVoxels += !tile.isVoxelValue();
    EXPECT_GT(tileVoxels, 0);  // the tile stays a tile in the marked grid: the test's tile branch runs
    VisibleCellTest test(*cells);
    std::uniform_real_distribution<double> at(-24.0, 270.0), side(-12.0, 12.0);
    int on = 0;
    for (int trial = 0; trial < 100000; ++trial) {
        const openvdb::Vec3d p(trial % 2 ? at(rng) : side(rng) - 6, side(rng), side(rng) + (trial % 3 ? 0 : 6));
        const bool expected = marked(*cells, int(std::floor(p.x())), int(std::floor(p.y())), int(std::floor(p.z())));
        ASSERT_EQ(test(p), expected) << p;
        on += expected;
    }
    EXPECT_GT(on, 10000);
    EXPECT_LT(on, 90000);
}

}  // namespace
}  // namespace weft
