// Leaf by leaf growth of a mask against OpenVDB's own dilation: the same
// voxels at every reach, and distances that are the Chebyshev distance.
#include <gtest/gtest.h>

#include <openvdb/tools/Morphology.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <vector>

#include "core/base/rng.hpp"
#include "core/volume/grid/leaf_reach.hpp"

using namespace weft;
using openvdb::Coord;

namespace {

// Scattered voxels over negative and positive coordinates, a slab across
// leaf boundaries and an active tile.
openvdb::MaskTree scatteredMask(std::uint64_t seed) {
    openvdb::MaskTree mask(false);
    Rng rng(seed);
    for (int i = 0; i < 60; ++i) mask.setValueOn(Coord(int(rng.next() % 90) - 45, int(rng.next() % 90) - 45, int(rng.next() % 90) - 45));
    mask.fill(openvdb::CoordBBox(Coord(-13, 2, 6), Coord(-9, 9, 7)), true, true);
    mask.fill(openvdb::CoordBBox(Coord(16), Coord(23)), true, true);
    return mask;
}

// The Chebyshev distance from voxel c to the nearest of `points`, by definition.
int chebyshevTo(const Coord& c, const std::vector<Coord>& points) {
    int cheb = 1 << 20;
    for (const Coord& p : points) cheb = std::min(cheb, std::max({std::abs(c.x() - p.x()), std::abs(c.y() - p.y()), std::abs(c.z() - p.z())}));
    return cheb;
}

}  // namespace

TEST(LeafReach, GrowingLeafByLeafIsOpenVdbsDilation) {
    for (const int reach : {0, 1, 2, 5, 16}) {
        openvdb::MaskTree mask = scatteredMask(9);
        mask.voxelizeActiveTiles();
        openvdb::MaskTree expected = mask;
        if (reach > 0) openvdb::tools::dilateActiveValues(expected, reach, openvdb::tools::NN_FACE_EDGE_VERTEX, openvdb::tools::EXPAND_TILES);
        openvdb::MaskTree grown(false);
        addLeavesNear(grown, mask, reach, [&](const Coord& origin, const std::uint8_t* d, const std::uint64_t* within) {
            auto leaf = std::make_unique<openvdb::MaskTree::LeafNodeType>(origin, false);
            for (openvdb::Index n = 0; n < openvdb::MaskTree::LeafNodeType::SIZE; ++n) {
                if (d[n] <= reach) leaf->setValueOn(n);
                EXPECT_EQ(d[n] <= reach, bool(within[n / 64] >> (n % 64) & 1)) << origin << " " << n;
            }
            return leaf;
        });
        EXPECT_EQ(grown.activeVoxelCount(), expected.activeVoxelCount()) << reach;
        openvdb::MaskTree diff = grown;
        diff.topologyDifference(expected);
        EXPECT_EQ(diff.activeVoxelCount(), 0u) << reach;
    }
}

TEST(LeafReach, DistancesAreChebyshevDistancesCappedPastTheReach) {
    const int reach = 6;
    openvdb::MaskTree mask(false);
    const std::vector<Coord> points = {Coord(0), Coord(3, -9, 17), Coord(-20, 4, 4), Coord(8, 8, -1)};
    for (const Coord& p : points) mask.setValueOn(p);
    LeafDistances distances(reach);
    int checked = 0;
    for (const Coord& origin : leafOriginsNear(mask, reach)) {
        distances.column(mask, origin, 1);
        const std::uint8_t* d = distances.leaf(0);
        for (openvdb::Index n = 0; n < 512; ++n) {
            const Coord c = origin + openvdb::MaskTree::LeafNodeType::offsetToLocalCoord(n);
            const int cheb = chebyshevTo(c, points);
            if (!d) {
                EXPECT_GT(cheb, reach) << c;
                continue;
            }
            EXPECT_EQ(int(d[n]), std::min(cheb, reach + 1)) << c;
            ++checked;
        }
    }
    EXPECT_GT(checked, 512 * 8);
    EXPECT_THROW(LeafDistances(kMaxLeafReach + 1), std::invalid_argument);
}

TEST(LeafReach, ColumnsGiveEveryLeafItsChebyshevDistances) {
    // Leaves stacked along z in one column, against the definition, at
    // reaches whose columns hold 8, 7, 6 and 4 leaves; features on the
    // stack's ends, just past them and in the leaves between.
    Rng rng(21);
    std::vector<Coord> points = {Coord(0), Coord(5, 2, 40), Coord(-3, 7, -6), Coord(1, 1, 57), Coord(12, -9, 30)};
    for (int i = 0; i < 6; ++i) points.emplace_back(int(rng.next() % 40) - 20, int(rng.next() % 40) - 20, int(rng.next() % 80) - 20);
    openvdb::MaskTree mask(false);
    for (const Coord& p : points) mask.setValueOn(p);
    for (const int reach : {0, 1, 7, 16}) {
        LeafDistances distances(reach);
        const int stack = LeafDistances::columnLeaves(reach);
        EXPECT_EQ(stack, (64 - 2 * reach) / 8);
        int checked = 0, nulls = 0;
        for (const Coord& base : {Coord(0, 0, -16), Coord(0, 0, 8), Coord(-8, 0, 24), Coord(8, -8, 0), Coord(-24, 16, -8), Coord(200, 0, 0)}) {
            distances.column(mask, base, stack);
            for (int s = 0; s < stack; ++s) {
                const Coord origin = base + Coord(0, 0, 8 * s);
                const std::uint8_t* d = distances.leaf(s);
                for (openvdb::Index n = 0; n < 512; ++n) {
                    const Coord c = origin + openvdb::MaskTree::LeafNodeType::offsetToLocalCoord(n);
                    const int cheb = chebyshevTo(c, points);
                    if (!d) {
                        EXPECT_GT(cheb, reach) << c << " reach " << reach;
                        continue;
                    }
                    EXPECT_EQ(int(d[n]), std::min(cheb, reach + 1)) << c << " reach " << reach;
                    EXPECT_EQ(cheb <= reach, bool(distances.within(s)[n / 64] >> (n % 64) & 1)) << c << " reach " << reach;
                    ++checked;
                }
                nulls += d == nullptr;
            }
        }
        EXPECT_GT(checked, 512 * 3) << reach;
        EXPECT_GE(nulls, stack) << reach;  // at least the column far from every feature
        EXPECT_THROW(distances.column(mask, Coord(0), stack + 1), std::invalid_argument);
        EXPECT_THROW(distances.column(mask, Coord(0), 0), std::invalid_argument);
    }
}

TEST(LeafReach, ColumnRunsStackLeavesOfOneXAndYWithinAColumn) {
    const std::vector<Coord> origins = {Coord(0, 0, 0),   Coord(0, 0, 8),  Coord(0, 0, 40), Coord(0, 0, 48),
                                        Coord(0, 0, 96),  Coord(0, 8, 0),  Coord(8, 8, 0),  Coord(8, 8, 16)};
    // Six leaves per column: z 0..40 is one, 48 starts the next and 96 one more; a new x or y always starts one.
    EXPECT_EQ(columnRuns(origins, 6), (std::vector<std::size_t>{0, 3, 4, 5, 6, 8}));
    EXPECT_EQ(columnRuns(origins, 1), (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8}));
    EXPECT_EQ(columnRuns({}, 6), (std::vector<std::size_t>{0}));
}

TEST(LeafReach, LeafOriginsNearAreEveryLeafAVoxelWithinReachCanLieIn) {
    // Against the definition: every leaf whose box comes within `reach`
    // voxels (Chebyshev) of a mask leaf's box, each once, sorted.
    openvdb::MaskTree mask = scatteredMask(7);
    mask.voxelizeActiveTiles();
    std::vector<Coord> maskLeaves;
    for (auto leaf = mask.cbeginLeaf(); leaf; ++leaf) maskLeaves.push_back(leaf->origin());
    for (int reach : {0, 1, 7, 8, 9, 16}) {
        std::vector<Coord> expected;
        for (const Coord& o : maskLeaves)
            for (int dx = -24; dx <= 24; dx += 8)
                for (int dy = -24; dy <= 24; dy += 8)
                    for (int dz = -24; dz <= 24; dz += 8) {
                        // Chebyshev distance between the two boxes' nearest voxels (<= 0: the same box)
                        const int distance = std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) - 7;
                        if (distance <= reach) expected.push_back(o + Coord(dx, dy, dz));
                    }
        std::sort(expected.begin(), expected.end());
        expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
        EXPECT_EQ(leafOriginsNear(mask, reach), expected) << reach;
    }
}
