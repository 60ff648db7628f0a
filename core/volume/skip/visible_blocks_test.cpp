// VisibleBlocks hands a march every stretch of a ray that crosses a visible
// cell, in order and without overlaps, and little else: a sample it leaves
// out would lose a visible lookup, one it hands twice would count twice.
#include "core/volume/skip/visible_blocks.hpp"

#include <gtest/gtest.h>

#include <openvdb/tools/Interpolation.h>

#include <cmath>
#include <random>

#include "core/volume/skip/visible_cells.hpp"
#include "core/volume/volume.hpp"

namespace weft {
namespace {

openvdb::FloatGrid::Ptr scatteredCells(std::mt19937& rng) {
    auto cells = openvdb::FloatGrid::create(0.0f);
    std::uniform_int_distribution<int> at(-30, 40);
    for (int n = 0; n < 800; ++n) cells->tree().setValueOn(openvdb::Coord(at(rng), at(rng), at(rng)), 1.0f);
    cells->tree().addTile(1, openvdb::Coord(128, 0, 0), 1.0f, true);  // a whole visible 128^3 node
    return cells;
}

IndexRay rayThrough(const Vec3d& from, const Vec3d& to) {
    IndexRay r;
    r.origin = from;
    r.dir = (to - from).unitSafe();
    r.t0 = 0, r.t1 = (to - from).length();
    return r;
}

TEST(VisibleBlocks, EveryVisibleCellARayCrossesIsInOneOrderedStretch) {
    initVdb();
    std::mt19937 rng(17);
    const openvdb::FloatGrid::Ptr cells = scatteredCells(rng);
    const auto blocks = VisibleBlocks::of(*cells);
    ASSERT_TRUE(blocks);
    EXPECT_GT(blocks->visibleBlockCount(), 40u);
    EXPECT_LT(blocks->visibleBlockCount(), blocks->blockCount() / 2);
    const openvdb::FloatGrid::ConstAccessor acc = cells->getConstAccessor();
    std::uniform_real_distribution<double> end(-40.0, 280.0), side(-40.0, 50.0);
    std::vector<RayInterval> out;
    long inside = 0, visibleSamples = 0, marched = 0;
    for (int trial = 0; trial < 400; ++trial) {
        Vec3d a(side(rng), side(rng), side(rng)), b(end(rng), side(rng), side(rng));
        if (trial % 4 == 0) b.y() = a.y(), b.z() = a.z();  // along an axis: zero direction components
        if (trial % 8 == 1) a = Vec3d(-20.5, 3.0, 3.0), b = Vec3d(40.5, 3.0, 3.0);  // on a block face's plane (y, z integer)
        const IndexRay ray = rayThrough(a, b);
        const double perU = trial % 3 ? 1.0 : 0.5;
        out.clear();
        blocks->intervals(ray, perU, out);
        for (std::size_t i = 0; i < out.size(); ++i) {
            ASSERT_LE(out[i].lo, out[i].hi);
            if (i > 0) {
                ASSERT_GT(out[i].lo, out[i - 1].hi);  // ordered, disjoint
            }
            EXPECT_GE(out[i].lo * perU, ray.t0 - 1e-9);
            EXPECT_LE(out[i].hi * perU, ray.t1 + 1e-9);
            marched += 1;
        }
        for (double t = ray.t0; t < ray.t1; t += 0.01) {
            const Vec3d p = ray.at(t);
            const openvdb::Coord c(int(std::floor(p.x())), int(std::floor(p.y())), int(std::floor(p.z())));
            bool covered = false;
            for (const RayInterval& in : out) covered = covered || (t >= in.lo * perU && t <= in.hi * perU);
            inside += covered;
            if (!acc.isValueOn(c)) continue;
            ++visibleSamples;
            ASSERT_TRUE(covered) << "trial " << trial << " t " << t << " cell " << c;
        }
    }
    EXPECT_GT(visibleSamples, 3000);
    EXPECT_GT(marched, 100);
    EXPECT_LT(inside, 40 * visibleSamples);  // the boxes are tight: the scattered cells are not marched as whole blocks
}

// Far from anything visible a ray leaps over empty blocks by their
// distance to the nearest visible one; it must land short of every visible
// cell, however the ray meets them.
TEST(VisibleBlocks, LeapsOverEmptySpaceButNotOverAVisibleCell) {
    initVdb();
    auto cells = openvdb::FloatGrid::create(0.0f);
    const openvdb::Coord far[] = {{0, 0, 0}, {203, 5, 3}, {100, 180, 7}, {60, 61, 230}, {231, 201, 190}};
    for (const openvdb::Coord& c : far) cells->tree().setValueOn(c, 1.0f);
    const auto blocks = VisibleBlocks::of(*cells);
    ASSERT_TRUE(blocks);
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> jitter(0.02, 0.98), outside(-20.0, 260.0);
    std::vector<RayInterval> out;
    for (int trial = 0; trial < 2000; ++trial) {
        // Through a point inside one of the cells, from and to anywhere around the grid.
        const openvdb::Coord c = far[trial % 5];
        const Vec3d through = c.asVec3d() + Vec3d(jitter(rng), jitter(rng), jitter(rng));
        const Vec3d from(outside(rng), outside(rng), outside(rng));
        IndexRay ray = rayThrough(from, through);
        const double tCell = (through - from).length();
        ray.t1 = tCell + 300.0;
        out.clear();
        blocks->intervals(ray, 1.0, out);
        bool covered = false;
        for (const RayInterval& in : out) covered = covered || (tCell >= in.lo && tCell <= in.hi);
        ASSERT_TRUE(covered) << "trial " << trial << " cell " << c << " from " << from;
        ASSERT_LE(out.size(), 5u);
    }
}

// The blocks' cell test answers as the cells grid does (VisibleCellTest
// descends its tree): inside and around leaves, in a visible tile, on both
// sides of the origin, a leaf with no active voxel, and far outside.
TEST(VisibleBlocks, CellTestAgreesWithTheCellsGrid) {
    initVdb();
    std::mt19937 rng(29);
    const openvdb::FloatGrid::Ptr cells = scatteredCells(rng);
    cells->tree().touchLeaf(openvdb::Coord(-24, 16, 8));  // a leaf, none of its voxels active
    const auto blocks = VisibleBlocks::of(*cells);
    ASSERT_TRUE(blocks);
    VisibleCellTest tree(*cells);
    // A third each: around the scattered cells, around the tile, anywhere.
    std::uniform_real_distribution<double> cellsRegion(-33.0, 43.0), tileRegion(126.0, 138.0), anywhere(-45.0, 270.0);
    int visibleCells = 0, visibleTile = 0;
    for (int n = 0; n < 600000; ++n) {
        auto& d = n % 3 == 0 ? cellsRegion : n % 3 == 1 ? tileRegion : anywhere;
        const Vec3d p(d(rng), d(rng) - (n % 3 == 1 ? 128.0 : 0.0), d(rng) - (n % 3 == 1 ? 128.0 : 0.0));
        const bool expected = tree(p);
        ASSERT_EQ(blocks->cellVisible(p), expected) << p;
        (p.x() < 100 ? visibleCells : visibleTile) += expected;
    }
    EXPECT_GT(visibleCells, 100);  // leaves' cells, not only hidden ones
    EXPECT_GT(visibleTile, 10000);
    EXPECT_FALSE(blocks->cellVisible(Vec3d(-1e6, 0, 0)));
    EXPECT_FALSE(blocks->cellVisible(Vec3d(1e6, 1e6, 1e6)));
}

TEST(VisibleBlocks, NothingVisibleOrTooManyBlocksLeavesItToTheHdda) {
    initVdb();
    auto none = openvdb::FloatGrid::create(0.0f);
    EXPECT_FALSE(VisibleBlocks::of(*none));
    auto wide = openvdb::FloatGrid::create(0.0f);
    wide->tree().setValueOn(openvdb::Coord(0, 0, 0), 1.0f);
    wide->tree().setValueOn(openvdb::Coord(800, 800, 800), 1.0f);  // 101^3 blocks
    EXPECT_FALSE(VisibleBlocks::of(*wide, 1000000));
    const auto fits = VisibleBlocks::of(*wide, 2000000);
    ASSERT_TRUE(fits);
    EXPECT_EQ(fits->blockCount(), 101u * 101u * 101u);
    EXPECT_EQ(fits->visibleBlockCount(), 2u);
}

// VisibleBlocks::reaching must hand a march every sample whose trilinear
// lookup reaches the cutoff: values above and below it, negative ones, an
// inactive voxel above it, a tile, on both sides of the origin.
openvdb::FloatGrid::Ptr densityAroundTheOrigin(std::mt19937& rng) {
    auto grid = openvdb::FloatGrid::create(0.0f);
    std::uniform_int_distribution<int> at(-40, 40);
    std::uniform_real_distribution<float> value(-0.2f, 1.0f);
    for (int n = 0; n < 600; ++n) grid->tree().setValueOn(openvdb::Coord(at(rng), at(rng), at(rng)), value(rng));
    grid->tree().setValueOff(openvdb::Coord(-17, 9, 33), 0.8f);  // inactive, yet read by lookups
    grid->tree().addTile(1, openvdb::Coord(128, 0, 0), 0.5f, true);  // a whole 128^3 node at 0.5
    return grid;
}

TEST(VisibleBlocks, ReachingHandsEveryLookupAtTheCutoffToTheMarch) {
    initVdb();
    std::mt19937 rng(29);
    const openvdb::FloatGrid::Ptr grid = densityAroundTheOrigin(rng);
    const float cutoff = 0.3f;
    const auto blocks = VisibleBlocks::reaching(*grid, cutoff);
    ASSERT_TRUE(blocks);
    EXPECT_LT(blocks->visibleBlockCount(), blocks->blockCount() / 2);
    const openvdb::FloatGrid::ConstAccessor acc = grid->getConstAccessor();
    std::uniform_real_distribution<double> end(-50.0, 270.0), side(-50.0, 50.0);
    std::vector<RayInterval> out;
    long reaching = 0, covered = 0;
    for (int trial = 0; trial < 400; ++trial) {
        Vec3d a(side(rng), side(rng), side(rng)), b(end(rng), side(rng), side(rng));
        if (trial % 4 == 0) b.y() = a.y(), b.z() = a.z();  // along an axis
        if (trial % 8 == 1) a = Vec3d(-17.5, 8.5, 32.5), b = Vec3d(-16.0, 10.0, 34.0);  // through the inactive voxel's cells
        const IndexRay ray = rayThrough(a, b);
        out.clear();
        blocks->intervals(ray, 1.0, out);
        for (std::size_t i = 1; i < out.size(); ++i) ASSERT_GT(out[i].lo, out[i - 1].hi);
        for (double t = ray.t0; t < ray.t1; t += 0.01) {
            bool in = false;
            for (const RayInterval& iv : out) in = in || (t >= iv.lo && t <= iv.hi);
            covered += in;
            if (!(openvdb::tools::BoxSampler::sample(acc, ray.at(t)) >= cutoff)) continue;
            ++reaching;
            ASSERT_TRUE(in) << "trial " << trial << " t " << t << " at " << ray.at(t);
        }
    }
    EXPECT_GT(reaching, 2000);
    EXPECT_LT(covered, 20 * reaching);  // little besides
}

// Within::ActiveBlocks keeps to the leaves with active voxels (the ones
// OpenVDB's intersector marches): a voxel on a leaf's low face spills its
// cells into the block below only where that block is such a leaf too.
TEST(VisibleBlocks, ReachingWithinActiveBlocksKeepsToLeavesWithActiveVoxels) {
    initVdb();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->tree().setValueOn(openvdb::Coord(3, 3, 3), 0.8f);    // block 0
    grid->tree().setValueOn(openvdb::Coord(8, 3, 3), 0.7f);    // block 8's low face: cell 7 of block 0
    grid->tree().setValueOn(openvdb::Coord(24, 3, 3), 0.7f);   // block 24's low face: cell 23 of block 16, no leaf
    grid->tree().setValueOff(openvdb::Coord(40, 3, 3), 0.9f);  // a leaf without active voxels
    const IndexRay ray = rayThrough(Vec3d(-5.0, 3.5, 3.5), Vec3d(60.0, 3.5, 3.5));
    const auto coversX = [&](VisibleBlocks::Within within, double x) {
        const auto blocks = VisibleBlocks::reaching(*grid, 0.5f, within);
        std::vector<RayInterval> out;
        blocks->intervals(ray, 1.0, out);
        const double t = x + 5.0;
        for (const RayInterval& in : out)
            if (t >= in.lo && t <= in.hi) return true;
        return false;
    };
    for (const auto within : {VisibleBlocks::Within::Anywhere, VisibleBlocks::Within::ActiveBlocks}) {
        for (const double x : {2.5, 3.5, 7.5, 8.5, 24.5}) EXPECT_TRUE(coversX(within, x)) << x;
        for (const double x : {-2.0, 12.0, 30.0, 50.0}) EXPECT_FALSE(coversX(within, x)) << x;
    }
    for (const double x : {23.5, 39.5, 40.5}) {
        EXPECT_TRUE(coversX(VisibleBlocks::Within::Anywhere, x)) << x;
        EXPECT_FALSE(coversX(VisibleBlocks::Within::ActiveBlocks, x)) << x;
    }
}

TEST(VisibleBlocks, ReachingNothingSkipsEverythingAndABackgroundAtTheCutoffSkipsNothing) {
    initVdb();
    auto low = openvdb::FloatGrid::create(0.0f);
    low->tree().setValueOn(openvdb::Coord(3, 4, 5), 0.1f);
    const auto none = VisibleBlocks::reaching(*low, 0.5f);
    ASSERT_TRUE(none);
    EXPECT_EQ(none->blockCount(), 0u);
    std::vector<RayInterval> out;
    none->intervals(rayThrough(Vec3d(-5.0), Vec3d(20.0)), 1.0, out);
    EXPECT_TRUE(out.empty());
    EXPECT_FALSE(VisibleBlocks::reaching(*openvdb::FloatGrid::create(0.5f), 0.5f));  // empty space reaches it
    auto wide = openvdb::FloatGrid::create(0.0f);
    wide->tree().setValueOn(openvdb::Coord(0, 0, 0), 1.0f);
    wide->tree().setValueOn(openvdb::Coord(800, 800, 800), 1.0f);
    EXPECT_FALSE(VisibleBlocks::reaching(*wide, 0.5f, VisibleBlocks::Within::Anywhere, 1000000));  // too many blocks
}

}  // namespace
}  // namespace weft
