// The precomputed oracles: the distance transform of a feature mask, what
// each oracle marks as a feature on volumes with known structure, and that
// adaptive renders driven by them stay close to volume.preint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/base/rng.hpp"
#include "oracles/feature_distance.hpp"
#include "oracles/oracle_cache.hpp"
#include "tests/support/render_helpers.hpp"

using namespace weft;
using openvdb::Coord;

namespace {

// A fog volume: density 1 in [lo, hi]^3 voxels, 0 elsewhere; extinction
// 0 at density 0 rising to `peak` at density 1.
Volume boxVolume(int lo, int hi, double peak = 0.5) {
    initVdb();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    grid->tree().fill(openvdb::CoordBBox(Coord(lo), Coord(hi)), 1.0f, true);
    grid->tree().voxelizeActiveTiles();
    Volume v;
    v.grid = grid;
    v.tf = TransferFunction(0, 1, {{0, {1, 1, 1}, 0}, {1, {1, 1, 1}, peak}});
    computeStatistics(v);
    return v;
}

float distanceAt(const OracleField& f, const Coord& c) { return f.atVoxel(c); }

int chebyshev(const Coord& a, const Coord& b) {
    return std::max({std::abs(a.x() - b.x()), std::abs(a.y() - b.y()), std::abs(a.z() - b.z())});
}

}  // namespace

// The field is grown only as far as the volume reaches (lookups stay inside
// it), so each test's volume covers the voxels it looks up.
TEST(FeatureDistance, RingsGrowByOneVoxelUpToTheCap) {
    const Volume v = boxVolume(-12, 12);
    openvdb::MaskGrid features(false);
    features.tree().setValueOn(Coord(0));
    const OracleField f = distanceToFeatures(features, {v, 1.0, 3, 0.01});
    for (int k = 0; k <= 12; ++k) {
        EXPECT_FLOAT_EQ(distanceAt(f, Coord(k, 0, 0)), float(std::clamp(k, 1, 8))) << k;
        EXPECT_FLOAT_EQ(distanceAt(f, Coord(-k, k, -k)), float(std::clamp(k, 1, 8))) << k;
    }
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(1000, 0, 0)), 8.0f);
}

TEST(FeatureDistance, RespectsSpacingAndLmax) {
    const Volume v = boxVolume(0, 1);
    openvdb::MaskGrid features(false);
    features.tree().setValueOn(Coord(0));
    const OracleField f = distanceToFeatures(features, {v, 0.5, 2, 0.01});  // cap 2 voxels
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(0)), 0.5f);
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(1, 0, 0)), 1.0f);
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(5, 3, 0)), 2.0f);
}

TEST(FeatureDistance, NeverExceedsTheEuclideanDistanceToAFeature) {
    const Volume v = boxVolume(-10, 50);
    Rng rng(7);
    openvdb::MaskGrid features(false);
    std::vector<Coord> points;
    for (int i = 0; i < 12; ++i) {
        points.emplace_back(int(rng.next() % 40), int(rng.next() % 40), int(rng.next() % 40));
        features.tree().setValueOn(points.back());
    }
    const OracleField f = distanceToFeatures(features, {v, 1.0, 4, 0.01});
    for (int trial = 0; trial < 3000; ++trial) {
        const Coord c(int(rng.next() % 60) - 10, int(rng.next() % 60) - 10, int(rng.next() % 60) - 10);
        double euclid = 1e9;
        int cheb = 1 << 20;
        for (const Coord& p : points) {
            euclid = std::min(euclid, (c - p).asVec3d().length());
            cheb = std::min(cheb, chebyshev(c, p));
        }
        const float d = distanceAt(f, c);
        EXPECT_LE(d, std::max(1.0, euclid) + 1e-6) << c;
        EXPECT_FLOAT_EQ(d, float(std::clamp(cheb, 1, 16))) << c;
    }
}

TEST(FeatureDistance, StopsGrowingAtTheVolumesExtent) {
    const Volume v = boxVolume(0, 7);  // index box [-1, 8]^3
    openvdb::MaskGrid features(false);
    features.tree().setValueOn(Coord(0));
    // A cap of 64 * 2^6 voxels: grown ring by ring to the cap, the field would fill billions of voxels.
    const OracleField f = distanceToFeatures(features, {v, 64.0, 6, 0.01});
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(8, 8, 8)), 64.0f);
    EXPECT_LT(f.rings->activeVoxelCount(), openvdb::Index64(64 * 64 * 64));
}

// The field by blocks (leaf by leaf, in parallel) equals the field grown
// ring by ring, voxel for voxel: scattered voxels, an active tile, a slab,
// negative coordinates, fractional spacings, one ring up to the most blocks
// take, and rings cut short by the volume's extent.
TEST(FeatureDistance, BlocksAndRingsGiveTheSameField) {
    const Volume wide = boxVolume(-40, 40), small = boxVolume(0, 5);
    Rng rng(3);
    openvdb::MaskGrid features(false);
    for (int i = 0; i < 40; ++i) features.tree().setValueOn(Coord(int(rng.next() % 70) - 35, int(rng.next() % 70) - 35, int(rng.next() % 70) - 35));
    features.tree().fill(openvdb::CoordBBox(Coord(8), Coord(15)), true, true);  // stays an active tile
    features.tree().fill(openvdb::CoordBBox(Coord(-20, -3, 5), Coord(-17, 4, 6)), true, true);
    struct Case { const Volume* volume; double spacing; int lmax; };
    for (const Case& c : {Case{&wide, 1.0, 0}, Case{&wide, 1.0, 3}, Case{&wide, 0.5, 2}, Case{&wide, 0.3, 3}, Case{&wide, 2.0, 3},
                          Case{&wide, 1.0, 4}, Case{&small, 8.0, 6}}) {
        const OracleContext ctx{*c.volume, c.spacing, c.lmax, 0.01};
        const OracleField rings = distanceFieldByRings(features, ctx), blocks = distanceFieldByBlocks(features, ctx);
        SCOPED_TRACE("spacing " + std::to_string(c.spacing) + " lmax " + std::to_string(c.lmax));
        EXPECT_EQ(blocks.constant, rings.constant);
        EXPECT_EQ(blocks.background(), rings.background());
        EXPECT_EQ(blocks.rings->activeVoxelCount(), rings.rings->activeVoxelCount());
        const auto a = rings.accessor(), b = blocks.accessor();
        int differ = 0;
        for (int x = -60; x <= 60; ++x)
            for (int y = -60; y <= 60; ++y)
                for (int z = -60; z <= 60; ++z) differ += rings.distances[a.getValue(Coord(x, y, z))] != blocks.distances[b.getValue(Coord(x, y, z))];
        EXPECT_EQ(differ, 0);
    }
}

// A moving volume's field: every distance (stored voxels, tiles and the
// background) shrinks by the reach, never below the minimum; a still one is
// handed back as it is.
TEST(FeatureDistance, PaddingByTheReachShrinksEveryDistance) {
    const Volume v = boxVolume(-12, 12);
    openvdb::MaskGrid features(false);
    features.tree().setValueOn(Coord(0));
    const OracleField f = distanceToFeatures(features, {v, 1.0, 4, 0.01});  // cap 16
    const OracleField padded = paddedByReach(f, 2.5, 1.0);
    for (int k = 0; k <= 12; ++k)
        EXPECT_FLOAT_EQ(distanceAt(padded, Coord(k, -k, 0)), std::max(1.0f, distanceAt(f, Coord(k, -k, 0)) - 2.5f)) << k;
    EXPECT_FLOAT_EQ(distanceAt(padded, Coord(5000, 0, 0)), 13.5f);
    EXPECT_FLOAT_EQ(padded.background(), 13.5f);
    EXPECT_FLOAT_EQ(paddedByReach(f, 1000, 1.0).atVoxel(Coord(7, 0, 0)), 1.0f);
    EXPECT_EQ(paddedByReach(f, 0, 1.0).rings, f.rings);
    OracleField constant;
    constant.constant = 8;
    EXPECT_FLOAT_EQ(paddedByReach(constant, 3, 1.0).constant, 5.0f);
    EXPECT_EQ(paddedByReach(constant, 3, 1.0).rings, nullptr);
}

TEST(TransferFunctionBounds, ExactOverPiecewiseLinearExtinction) {
    const TransferFunction tf(0, 10, {{0, {1, 1, 1}, 0}, {0.5, {1, 1, 1}, 2}, {1, {1, 1, 1}, 1}});
    auto b = tf.extinctionBounds(0, 10);
    EXPECT_DOUBLE_EQ(b[0], 0);
    EXPECT_DOUBLE_EQ(b[1], 2);
    b = tf.extinctionBounds(7.5, 10);  // s 0.75..1: 1.5 down to 1
    EXPECT_DOUBLE_EQ(b[0], 1);
    EXPECT_DOUBLE_EQ(b[1], 1.5);
    b = tf.extinctionBounds(2.5, 2.5);
    EXPECT_DOUBLE_EQ(b[0], 1);
    EXPECT_DOUBLE_EQ(b[1], 1);
    b = tf.extinctionBounds(-5, std::nan(""));  // NaN reads as empty, below range clamps
    EXPECT_DOUBLE_EQ(b[0], 0);
    EXPECT_DOUBLE_EQ(b[1], 0);
}

TEST(GradientAlphaOracle, FeaturesSitOnTheFacesOfAConstantBlock) {
    const Volume v = boxVolume(0, 47);
    const OracleField f = oracles().get("gradient_alpha").build({v, 1.0, 3, 0.01});
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(0, 20, 20)), 1.0f);    // face: opacity jumps
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(-1, 20, 20)), 1.0f);   // just outside the face
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(1, 20, 20)), 1.0f);    // central differences flag x = -1 and 0 only
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(5, 20, 20)), 5.0f);    // inside, 5 voxels from the face
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(24, 24, 24)), 8.0f);   // centre: constant, capped
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(-30, 20, 20)), 8.0f);  // far outside
}

TEST(GradientAlphaOracle, EpsilonAboveTheJumpLeavesNoFeatures) {
    // Slice opacity at density 1: 1 - e^-0.5 = 0.39; |gradient| 0.2 on faces,
    // 0.28 on edges, 0.34 at corners.
    const Volume v = boxVolume(0, 15, 0.5);
    const OracleField low = oracles().get("gradient_alpha").build({v, 1.0, 3, 0.1});
    const OracleField high = oracles().get("gradient_alpha").build({v, 1.0, 3, 0.35});
    EXPECT_FLOAT_EQ(distanceAt(low, Coord(0, 8, 8)), 1.0f);
    EXPECT_FLOAT_EQ(distanceAt(high, Coord(0, 8, 8)), 8.0f);
}

// The features read per 8^3 block (leaf buffers, a tile, the background
// beyond) are those of central differences taken voxel by voxel through an
// accessor, wherever the gradient is not within rounding of the threshold.
// Checked on a tree of leaves only and on one with an active tile, each
// with an inactive tile read beside the data.
TEST(GradientAlphaOracle, BlockwiseFeaturesMatchVoxelByVoxelDifferences) {
    initVdb();
    for (const bool activeTile : {false, true}) {
        SCOPED_TRACE(activeTile ? "with an active tile" : "leaves only");
        openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.1f);
        Rng rng(7);
        for (int x = -12; x < 20; ++x)
            for (int y = -4; y < 13; ++y)
                for (int z = 0; z < 9; ++z)
                    if (rng.uniform() < 0.7f) {
                        const float value = rng.uniform() < 0.5f ? 0.4f : rng.uniform();  // plateaus and noise
                        if (rng.uniform() < 0.9f) grid->tree().setValueOn(Coord(x, y, z), value);
                        else grid->tree().setValueOff(Coord(x, y, z), value);  // inactive but read by neighbours
                    }
        // Beside the data: an inactive tile with a value of its own, read by the voxels next to it.
        grid->tree().fill(openvdb::CoordBBox(Coord(24, 8, 0), Coord(31, 15, 7)), 0.6f, false);
        grid->tree().setValueOn(Coord(23, 9, 3), 0.2f);
        if (activeTile) grid->tree().fill(openvdb::CoordBBox(Coord(24, 0, 0), Coord(31, 7, 7)), 0.8f, true);
        ASSERT_EQ(grid->tree().activeTileCount() > 0, activeTile);
        Volume v;
        v.grid = grid;
        v.tf = TransferFunction(0, 1, {{0, {1, 1, 1}, 0}, {1, {1, 1, 1}, 0.9}});
        computeStatistics(v);
        const OracleContext ctx{v, 1.0, 3, 0.05};
        const Coord shift(16, -8, 24);
        const openvdb::MaskGrid::Ptr features = gradientFeatures(ctx, shift);
        const openvdb::MaskGrid::Ptr candidates = activeAndFaceNeighbours(*grid, shift);
        auto acc = grid->getConstAccessor();
        int checked = 0, marked = 0, rounding = 0;
        for (auto it = candidates->tree().cbeginValueOn(); it; ++it) {
            const Coord c = it.getCoord() - shift;
            double g2 = 0;
            for (int axis = 0; axis < 3; ++axis) {
                Coord lo = c, hi = c;
                --lo[axis], ++hi[axis];
                const double g = 0.5 * (sliceOpacity(v, 1.0, acc.getValue(hi)) - sliceOpacity(v, 1.0, acc.getValue(lo)));
                g2 += g * g;
            }
            const double threshold2 = ctx.epsilon * ctx.epsilon;
            if (std::abs(g2 - threshold2) < 1e-6) {
                ++rounding;
                continue;
            }
            ++checked, marked += g2 > threshold2;
            EXPECT_EQ(features->tree().isValueOn(it.getCoord()), g2 > threshold2) << c;
        }
        EXPECT_GT(checked, 4000);
        EXPECT_GT(marked, 500);
        EXPECT_LT(marked, checked - (activeTile ? 500 : 300));  // some candidates fall below the threshold
        const openvdb::Index64 count = features->tree().activeVoxelCount();  // and no feature outside the candidates
        EXPECT_GE(count, openvdb::Index64(marked));
        EXPECT_LE(count, openvdb::Index64(marked + rounding));
        EXPECT_TRUE(features->transform() == candidates->transform());
    }
}

TEST(VdbTopologyOracle, EmptySpaceIsFarOccupiedBricksAreDense) {
    const Volume v = boxVolume(0, 15);
    const OracleField f = oracles().get("vdb_topology").build({v, 1.0, 3, 0.01});
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(8, 8, 8)), 1.0f);     // inside: occupied brick
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(-2, 8, 8)), 2.0f);    // no brick out there: 2 from the occupied ones
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(-40, 8, 8)), 8.0f);
}

TEST(VdbTopologyOracle, TransparentValuesAreEmptyEverywhere) {
    Volume v = boxVolume(0, 15);
    v.tf = TransferFunction(0, 1, {{0, {1, 1, 1}, 0}, {1, {1, 1, 1}, 0}});
    const OracleField f = oracles().get("vdb_topology").build({v, 1.0, 3, 0.01});
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(8, 8, 8)), 8.0f);
}

TEST(MajorantOracle, SmoothBricksAreSkippedEvenWhenNotEmpty) {
    const Volume v = boxVolume(0, 47);
    const OracleField f = oracles().get("majorant").build({v, 1.0, 3, 0.01});
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(0, 20, 20)), 1.0f);    // boundary brick: opacity jumps across its apron
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(12, 20, 20)), 5.0f);   // interior brick, 5 from the boundary bricks (x <= 7)
    EXPECT_FLOAT_EQ(distanceAt(f, Coord(24, 24, 24)), 8.0f);   // 17 from any boundary brick: capped
}

TEST(Oracles, AFieldAroundTheIndexOriginIsTheMovedFieldAndKeepsOneTopNode) {
    // The same block of data around the index origin and moved far from it:
    // each oracle gives every voxel the same distance, and its tree over the
    // block around the origin keeps one top node, not one per octant.
    const Volume around = boxVolume(-20, 13, 0.5), moved = boxVolume(-20 + 4000, 13 + 4000, 0.5);
    for (const char* oracle : {"gradient_alpha", "vdb_topology", "majorant"}) {
        const OracleField a = oracles().get(oracle).build({around, 1.0, 3, 0.01});
        const OracleField b = oracles().get(oracle).build({moved, 1.0, 3, 0.01});
        ASSERT_TRUE(a.rings && b.rings) << oracle;
        EXPECT_EQ(a.rings->root().childCount(), 1u) << oracle;
        EXPECT_EQ(a.rings->activeVoxelCount(), b.rings->activeVoxelCount()) << oracle;
        int mismatches = 0;
        for (auto c = openvdb::CoordBBox(Coord(-32), Coord(25)).begin(); c; ++c)
            mismatches += distanceAt(a, *c) != distanceAt(b, *c + Coord(4000));
        EXPECT_EQ(mismatches, 0) << oracle;
        const auto acc = a.accessor();  // a lookup between voxels rounds to the nearest
        EXPECT_FLOAT_EQ(a.at(acc, openvdb::Vec3d(-15.4, 2.2, -0.6)), distanceAt(a, Coord(-15, 2, -1))) << oracle;
    }
}

TEST(Oracles, AVolumeNearTheEndOfIntRangeIsLookedUpWithoutLeavingIt) {
    // Its field holds it moved by almost all of int range: a lookup far on
    // the other side reads the background instead of overflowing.
    const Volume far = boxVolume(2000000000, 2000000040, 0.5);
    const OracleField f = oracles().get("gradient_alpha").build({far, 1.0, 3, 0.01});
    ASSERT_TRUE(f.rings);
    const auto acc = f.accessor();
    EXPECT_FLOAT_EQ(f.at(acc, openvdb::Vec3d(-1.0e9, 0, 0)), f.background());
    EXPECT_FLOAT_EQ(f.at(acc, openvdb::Vec3d(2000000020.2, 2000000019.9, 2000000020)), 8.0f);  // 20 voxels inside: capped
    EXPECT_FLOAT_EQ(f.at(acc, openvdb::Vec3d(2000000000, 2000000020, 2000000020)), 1.0f);     // on a face
}

TEST(Oracles, AdaptiveRendersStayWithinOne255thOfPreint) {
    const std::string smoke = std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb";
    const RenderOutcome ref = test::render(smoke, "96x96", {}, "volume.preint");
    for (const char* oracle : {"gradient_alpha", "vdb_topology", "majorant"}) {
        const RenderOutcome a = test::render(smoke, "96x96", {std::string("oracle=") + oracle}, "volume.adaptive3d");
        EXPECT_LT(test::rmse(a.image, ref.image), 1.0 / 255) << oracle;
        EXPECT_LT(a.counters.at("volume.samples"), ref.counters.at("volume.samples")) << oracle;
    }
}

TEST(Oracles, BuiltFieldsAndImagesIdenticalOnOneAndTwoThreads) {
    const std::string smoke = std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb";
    for (const char* oracle : {"gradient_alpha", "vdb_topology", "majorant"}) {
        const std::vector<std::string> sets{std::string("oracle=") + oracle};
        clearOracleCache();  // each render builds its own field
        const RenderOutcome a = test::render(smoke, "48x40", sets, "volume.adaptive3d", 1);
        clearOracleCache();
        const RenderOutcome b = test::render(smoke, "48x40", sets, "volume.adaptive3d", 2);
        EXPECT_EQ(a.image.data(), b.image.data()) << oracle;
        EXPECT_EQ(a.counters, b.counters) << oracle;
    }
}

TEST(Oracles, CoarseImagesStayWithinOne255thOfPreint) {
    // At 24x24 a pixel is several voxels wide: distances must then be
    // counted in pixel widths, or coarse pyramid levels skip features
    // lying between their rays.
    const std::string smoke = std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb";
    const RenderOutcome ref = test::render(smoke, "24x24", {}, "volume.preint");
    for (const char* oracle : {"gradient_alpha", "vdb_topology", "majorant"}) {
        const RenderOutcome a = test::render(smoke, "24x24", {std::string("oracle=") + oracle}, "volume.adaptive3d");
        EXPECT_LT(test::rmse(a.image, ref.image), 1.0 / 255) << oracle;
    }
}
