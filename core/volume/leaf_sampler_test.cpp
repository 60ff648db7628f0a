// LeafSampler reads the eight values of a trilinear lookup from the leaf
// that holds them; it must return exactly what OpenVDB's BoxSampler returns
// everywhere: inside leaves, on cells that straddle leaves, in tiles, in the
// background, at negative coordinates and far outside the tree.
#include "core/volume/leaf_sampler.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/volume/volume.hpp"

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

TEST(LeafSampler, EqualsBoxSamplerBitForBit) {
    const auto grid = gridOfLeavesAndTiles();
    const auto acc = grid->getConstAccessor();
    LeafSampler leaf(acc, grid->transform());
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> inside(-24.0, 24.0), tile(120.0, 260.0), far(-1e6, 1e6);
    int mismatches = 0, checked = 0;
    for (int i = 0; i < 200000; ++i) {
        auto& d = i % 4 == 3 ? tile : (i % 16 == 5 ? far : inside);
        const openvdb::Vec3d p(d(rng), d(rng), d(rng));
        const float expected = openvdb::tools::BoxSampler::sample(acc, p);
        mismatches += !sameBits(leaf.isSample(p), expected);
        ++checked;
    }
    EXPECT_EQ(mismatches, 0) << "of " << checked;
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
        ASSERT_TRUE(sameBits(leaf.isSample(p), openvdb::tools::BoxSampler::sample(acc, p))) << t;
    }
    // Exactly on leaf faces and cell corners.
    for (const openvdb::Vec3d p : {openvdb::Vec3d(7, 7, 7), openvdb::Vec3d(8, 8, 8), openvdb::Vec3d(-8, -1, 0),
                                   openvdb::Vec3d(6.999999, 0, 0), openvdb::Vec3d(-0.0, -0.0, -0.0)})
        EXPECT_TRUE(sameBits(leaf.isSample(p), openvdb::tools::BoxSampler::sample(acc, p))) << p;
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
        EXPECT_TRUE(sameBits(leaf.wsSample(p), box.wsSample(p))) << p;
    }
}

}  // namespace
}  // namespace weft
