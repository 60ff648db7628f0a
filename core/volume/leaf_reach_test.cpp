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
#include "core/volume/leaf_reach.hpp"

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

}  // namespace

TEST(LeafReach, GrowingLeafByLeafIsOpenVdbsDilation) {
    for (const int reach : {0, 1, 2, 5, 16}) {
        openvdb::MaskTree mask = scatteredMask(9);
        mask.voxelizeActiveTiles();
        openvdb::MaskTree expected = mask;
        if (reach > 0) openvdb::tools::dilateActiveValues(expected, reach, openvdb::tools::NN_FACE_EDGE_VERTEX, openvdb::tools::EXPAND_TILES);
        openvdb::MaskTree grown(false);
        addLeavesNear(grown, mask, reach, [&](const Coord& origin, const std::uint8_t* d) {
            auto leaf = std::make_unique<openvdb::MaskTree::LeafNodeType>(origin, false);
            for (openvdb::Index n = 0; n < openvdb::MaskTree::LeafNodeType::SIZE; ++n)
                if (d[n] <= reach) leaf->setValueOn(n);
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
        const std::uint8_t* d = distances.of(mask, origin);
        for (openvdb::Index n = 0; n < 512; ++n) {
            const Coord c = origin + openvdb::MaskTree::LeafNodeType::offsetToLocalCoord(n);
            int cheb = 1 << 20;
            for (const Coord& p : points)
                cheb = std::min(cheb, std::max({std::abs(c.x() - p.x()), std::abs(c.y() - p.y()), std::abs(c.z() - p.z())}));
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
