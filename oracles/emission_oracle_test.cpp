// Emission as an oracle feature: a glow that changes inside constant
// density keeps samples dense there, constant glow does not, and the oracle
// cache tells emitting volumes apart by their emission.
#include <gtest/gtest.h>

#include "core/scene/scene.hpp"
#include "oracles/feature_distance.hpp"
#include "oracles/oracle_cache.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/vdb_fixtures.hpp"

using namespace weft;

namespace {

// A 32^3 cube of constant density (no opacity gradient inside) whose
// emission steps from 0 to `glow` at z = 16, in the half x >= 16 only.
openvdb::Coord centreOf(const openvdb::CoordBBox& box) {
    const openvdb::Coord d = box.dim();
    return box.min() + openvdb::Coord(d.x() / 2, d.y() / 2, d.z() / 2);
}

Volume glowingCube(float glow) {
    test::TempDir dir;
    test::writeSlabVdb(dir / "cube.vdb", 32, 32, 0.1);
    Volume v = loadScene((dir / "cube.vdb").string()).volumes.front();
    auto emission = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    emission->setTransform(v.grid->transform().copy());
    const openvdb::CoordBBox box = v.grid->evalActiveVoxelBoundingBox();
    emission->denseFill(openvdb::CoordBBox(box.min(), box.max()), openvdb::Vec3s(0.0f), true);
    const openvdb::Coord mid = centreOf(box);
    emission->denseFill(openvdb::CoordBBox(openvdb::Coord(mid.x(), box.min().y(), mid.z()), box.max()), openvdb::Vec3s(glow, glow * 0.5f, 0.0f), true);
    v.emission = emission;
    return v;
}

float distanceAt(const OracleField& f, const openvdb::Coord& c) {
    const auto acc = f.accessor();
    return f.at(acc, openvdb::Vec3d(c.x(), c.y(), c.z()));
}

}  // namespace

TEST(EmissionOracle, AChangingGlowIsAFeatureWhereTheDensityIsFlat) {
    const Volume plain = [] {
        Volume v = glowingCube(1.0f);
        v.emission = nullptr;
        return v;
    }();
    const Volume glowing = glowingCube(1.0f);
    const openvdb::CoordBBox box = glowing.grid->evalActiveVoxelBoundingBox();
    const openvdb::Coord mid = centreOf(box);
    const openvdb::Coord step(mid.x() + 8, mid.y(), mid.z());      // on the glow's step
    const openvdb::Coord dark(box.min().x() + 4, mid.y(), mid.z());  // far from any glow or edge
    for (const char* name : {"gradient_alpha", "majorant", "vdb_topology"}) {
        const OracleInfo& oracle = oracles().get(name);
        const OracleField without = oracle.build({plain, 1.0, 3, 0.01});
        const OracleField with = oracle.build({glowing, 1.0, 3, 0.01});
        ASSERT_TRUE(with.rings) << name;
        EXPECT_EQ(distanceAt(with, step), 1.0f) << name;  // the step is sampled densely
        if (without.rings) {
            EXPECT_GE(distanceAt(without, step), distanceAt(with, step)) << name;
        }
    }
    // gradient_alpha: the flat dark interior stays coarse, glow or not.
    const OracleField with = oracles().get("gradient_alpha").build({glowing, 1.0, 3, 0.01});
    EXPECT_GT(distanceAt(with, dark), 1.0f);
    // A glow too faint for epsilon is no feature.
    const Volume faint = glowingCube(1e-4f);
    const OracleField faintField = oracles().get("gradient_alpha").build({faint, 1.0, 3, 0.01});
    EXPECT_GT(distanceAt(faintField, step), 1.0f);
}

TEST(EmissionOracle, TheCacheKeysAnEmittingVolumeByItsEmission) {
    clearOracleCache();
    const Volume a = glowingCube(1.0f);
    Volume same = a;
    same.emission = glowingCube(1.0f).emission;  // another grid, equal content
    Volume brighter = a;
    brighter.emission = glowingCube(2.0f).emission;
    Volume none = a;
    none.emission = nullptr;
    const OracleInfo& oracle = oracles().get("gradient_alpha");
    EXPECT_FALSE(sharedOracleField(oracle, {a, 1.0, 3, 0.01}).reused);
    EXPECT_TRUE(sharedOracleField(oracle, {same, 1.0, 3, 0.01}).reused);
    EXPECT_FALSE(sharedOracleField(oracle, {brighter, 1.0, 3, 0.01}).reused);
    EXPECT_FALSE(sharedOracleField(oracle, {none, 1.0, 3, 0.01}).reused);
}
