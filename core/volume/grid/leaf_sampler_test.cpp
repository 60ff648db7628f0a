// LeafSampler reads the eight values of a trilinear lookup from the leaves
// that hold them and interpolates in float; it must agree with OpenVDB's
// BoxSampler to float rounding everywhere (inside leaves, on cells that
// straddle leaves, in tiles, in the background, at negative coordinates
// and far outside the tree), and exactly at voxel centres and in constant
// regions, where no rounding happens.
#include "core/volume/grid/leaf_sampler.hpp"

#include <openvdb/tools/Interpolation.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/volume/grid/vdb_init.hpp"

namespace weft {
namespace {

// Leaves of noise around the origin (negative coordinates too), an active
// 128^3 tile, and a background of 0.5.
openvdb::FloatGrid::Ptr gridOfLeavesAndTiles() {
    initVdb();
    auto grid = openvdb::FloatGrid::create(0.5f);
    auto acc = grid->getAccessor();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> value(-2.0f, 3.0f);
    for (int x = -20; x < 20; ++x)
        for (int y = -12; y < 20; ++y)
            for (int z = -20; z < 12; ++z)
                if ((x * 7 + y * 3 + z) % 5 != 0) acc.setValue(openvdb::Coord(x, y, z), value(rng));
    grid->tree().fill(openvdb::CoordBBox({128, 0, 0}, {255, 127, 127}), 1.25f, true);
    return grid;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Float rounding of a seven-lerp chain over values within [-2, 3]: a few
// ulps of 3 (2.4e-7 each).
constexpr float kRounding = 1.5e-6f;

TEST(LeafSampler, AgreesWithBoxSamplerToFloatRounding) {
    const auto grid = gridOfLeavesAndTiles();
    const auto acc = grid->getConstAccessor();
    LeafSampler leaf(acc, grid->transform());
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> inside(-24.0, 24.0), tile(120.0, 260.0), far(-1e6, 1e6);
    int mismatches = 0, checked = 0, inexact = 0;
    for (int i = 0; i < 200000; ++i) {
        auto& d = i % 4 == 3 ? tile : (i % 16 == 5 ? far : inside);
        const openvdb::Vec3d p(d(rng), d(rng), d(rng));
        const float expected = openvdb::tools::BoxSampler::sample(acc, p), got = leaf.isSample(p);
        mismatches += !(std::abs(got - expected) <= kRounding);
        inexact += !sameBits(got, expected);
        ++checked;
        // Cells wholly in a constant region (the tile, the background) interpolate nothing.
        const auto within = [&](double lo, double hi) { return p.x() >= lo && p.y() >= lo && p.z() >= lo && p.x() < hi && p.y() < hi && p.z() < hi; };
        const bool inTile = p.x() >= 128 && p.x() < 255 && p.y() >= 0 && p.y() < 127 && p.z() >= 0 && p.z() < 127;
        if (inTile || !within(-30, 260)) {
            ASSERT_TRUE(sameBits(got, expected)) << p;
        }
    }
    EXPECT_EQ(mismatches, 0) << "of " << checked;
    EXPECT_GT(inexact, 0);  // the rounding is float's: the check above is not vacuous
}

TEST(LeafSampler, VoxelCentresAreTheVoxelsExactly) {
    const auto grid = gridOfLeavesAndTiles();
    const auto acc = grid->getConstAccessor();
    LeafSampler leaf(acc, grid->transform());
    for (int x = -22; x < 22; x += 3)
        for (int y = -14; y < 22; y += 1)
            for (int z = -22; z < 14; z += 5)
                ASSERT_TRUE(sameBits(leaf.isSample(openvdb::Vec3d(x, y, z)), acc.getValue(openvdb::Coord(x, y, z)))) << x << "," << y << "," << z;
}

// A march along one ray, the access pattern the cache is for: every step
// revisits the leaf of the one before, and crosses into the next.
TEST(LeafSampler, MarchAcrossLeafFacesAndIntoTheBackground) {
    const auto grid = gridOfLeavesAndTiles();
    const auto acc = grid->getConstAccessor();
    LeafSampler leaf(acc, grid->transform());
    const openvdb::Vec3d origin(-30.3, -7.9, 3.2), dir(0.81, 0.37, -0.45);
    for (double t = 0; t < 80; t += 0.173) {
        const openvdb::Vec3d p = origin + dir * t;
        ASSERT_NEAR(leaf.isSample(p), openvdb::tools::BoxSampler::sample(acc, p), kRounding) << t;
    }
    // Exactly on leaf faces and cell corners.
    for (const openvdb::Vec3d p : {openvdb::Vec3d(7, 7, 7), openvdb::Vec3d(8, 8, 8), openvdb::Vec3d(-8, -1, 0),
                                   openvdb::Vec3d(6.999999, 0, 0), openvdb::Vec3d(-0.0, -0.0, -0.0)})
        EXPECT_NEAR(leaf.isSample(p), openvdb::tools::BoxSampler::sample(acc, p), kRounding) << p;
}

TEST(LeafSampler, WorldSamplesFollowTheTransform) {
    auto grid = gridOfLeavesAndTiles();
    grid->setTransform(openvdb::math::Transform::createLinearTransform(openvdb::math::Mat4d(
        0.5, 0.1, 0.0, 0.0, 0.0, 0.25, 0.0, 0.0, 0.0, 0.0, 0.7, 0.0, 1.0, -2.0, 3.0, 1.0)));
    const auto acc = grid->getConstAccessor();
    LeafSampler leaf(acc, grid->transform());
    openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler> box(acc, grid->transform());
    for (double t = -10; t < 10; t += 0.37) {
        const openvdb::Vec3d p(t, 0.3 * t - 1, 2 - 0.5 * t);
        EXPECT_NEAR(leaf.wsSample(p), box.wsSample(p), kRounding) << p;
    }
}

}  // namespace
}  // namespace weft

namespace weft {
namespace {

// A dense copy changes where the eight values come from, not what they
// are: lookups through it equal the leaves' bit for bit, inside the copy,
// on its edges (cells half in it go to the leaves), and outside it.
TEST(DenseCopy, LookupsThroughItEqualTheLeavesBitForBit) {
    initVdb();
    auto grid = openvdb::FloatGrid::create(0.5f);
    auto acc = grid->getAccessor();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> value(-2.0f, 3.0f);
    for (int x = -9; x < 30; ++x)
        for (int y = -17; y < 15; ++y)
            for (int z = -3; z < 21; ++z)
                if ((x + 2 * y + 3 * z) % 7 != 0) acc.setValue(openvdb::Coord(x, y, z), value(rng));
    grid->tree().fill(openvdb::CoordBBox({32, -16, 0}, {39, -9, 7}), 1.25f, true);  // a tile beside the leaves
    const auto dense = DenseCopy<openvdb::FloatGrid>::of(*grid);
    ASSERT_NE(dense, nullptr);
    const auto constAcc = grid->getConstAccessor();
    LeafSampler leaves(constAcc, grid->transform()), both(constAcc, grid->transform());
    both.useDense(dense.get());
    std::uniform_real_distribution<double> around(-14.0, 45.0);
    int inCopy = 0, differ = 0;
    for (int i = 0; i < 200000; ++i) {
        const openvdb::Vec3d p(around(rng), around(rng), around(rng));
        inCopy += dense->holdsCell(floorToInt(p.x()), floorToInt(p.y()), floorToInt(p.z()));
        differ += !sameBits(leaves.isSample(p), both.isSample(p));
    }
    EXPECT_EQ(differ, 0);
    EXPECT_GT(inCopy, 20000);   // the copy served many lookups...
    EXPECT_LT(inCopy, 180000);  // ...and the leaves the others
}

TEST(DenseCopy, SparseOrHugeGridsKeepTheirTree) {
    initVdb();
    auto sparse = openvdb::FloatGrid::create(0.0f);
    sparse->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
    sparse->tree().setValue(openvdb::Coord(200, 200, 200), 1.0f);  // two leaves in a 201^3 box
    EXPECT_EQ(DenseCopy<openvdb::FloatGrid>::of(*sparse), nullptr);
    EXPECT_EQ(DenseCopy<openvdb::FloatGrid>::of(*openvdb::FloatGrid::create(0.0f)), nullptr);  // nothing active
    auto full = openvdb::FloatGrid::create(0.0f);
    full->tree().fill(openvdb::CoordBBox({0, 0, 0}, {63, 63, 63}), 1.0f, true);
    full->tree().voxelizeActiveTiles();
    EXPECT_NE(DenseCopy<openvdb::FloatGrid>::of(*full), nullptr);
    EXPECT_EQ(DenseCopy<openvdb::FloatGrid>::of(*full, 1000), nullptr);  // more voxels than allowed
}

}  // namespace
}  // namespace weft
