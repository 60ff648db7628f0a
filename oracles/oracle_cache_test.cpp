// The oracle cache: an equal request is served from it (the same field, not
// a copy), anything the field depends on misses, and a render reports which
// happened in its counters; renders from cached fields equal fresh ones.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/scene/scene.hpp"
#include "oracles/oracle_cache.hpp"
#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/vdb_fixtures.hpp"

using namespace weft;

namespace {

const OracleInfo& gradientAlpha() { return oracles().get("gradient_alpha"); }

Volume loadedVolume(const std::string& path) { return loadScene(path).volumes.front(); }

}  // namespace

TEST(OracleCache, AnEqualRequestIsServedFromTheCache) {
    clearOracleCache();
    test::TempDir dir;
    test::writeProceduralVdb(dir / "cloud.vdb", "cloud", 24);
    const Volume v = loadedVolume((dir / "cloud.vdb").string());
    const SharedOracleField first = sharedOracleField(gradientAlpha(), {v, 1.0, 3, 0.01});
    const SharedOracleField second = sharedOracleField(gradientAlpha(), {v, 1.0, 3, 0.01});
    EXPECT_FALSE(first.reused);
    EXPECT_TRUE(second.reused);
    ASSERT_TRUE(first.field.rings);
    EXPECT_EQ(first.field.rings.get(), second.field.rings.get());
}

TEST(OracleCache, EveryInputOfTheFieldMisses) {
    clearOracleCache();
    test::TempDir dir;
    test::writeProceduralVdb(dir / "cloud.vdb", "cloud", 24);
    const Volume v = loadedVolume((dir / "cloud.vdb").string());
    sharedOracleField(gradientAlpha(), {v, 1.0, 3, 0.01});
    EXPECT_FALSE(sharedOracleField(gradientAlpha(), {v, 1.0, 3, 0.02}).reused);   // epsilon
    EXPECT_FALSE(sharedOracleField(gradientAlpha(), {v, 0.5, 3, 0.01}).reused);   // spacing
    EXPECT_FALSE(sharedOracleField(gradientAlpha(), {v, 1.0, 2, 0.01}).reused);   // lmax
    EXPECT_FALSE(sharedOracleField(oracles().get("majorant"), {v, 1.0, 3, 0.01}).reused);
    Volume otherTf = v;
    otherTf.tf = TransferFunction(v.tf.rangeMin(), v.tf.rangeMax(), {{0, {1, 1, 1}, 0}, {1, {1, 1, 1}, 3.0}});
    EXPECT_FALSE(sharedOracleField(gradientAlpha(), {otherTf, 1.0, 3, 0.01}).reused);
    Volume moved = v;
    auto grid = std::make_shared<openvdb::FloatGrid>(*v.grid);  // the same file's grid, scaled
    grid->transform().preScale(2.0);
    moved.grid = grid;
    EXPECT_FALSE(sharedOracleField(gradientAlpha(), {moved, 1.0, 3, 0.01}).reused);
}

// Each frame of a sequence loads its volume again: an unchanged file is found,
// a rewritten one is not.
TEST(OracleCache, AFreshLoadOfTheSameFileIsFoundAndARewrittenFileIsNot) {
    clearOracleCache();
    test::TempDir dir;
    const std::string path = (dir / "cloud.vdb").string();
    test::writeProceduralVdb(path, "cloud", 24);
    EXPECT_FALSE(sharedOracleField(gradientAlpha(), {loadedVolume(path), 1.0, 3, 0.01}).reused);
    EXPECT_TRUE(sharedOracleField(gradientAlpha(), {loadedVolume(path), 1.0, 3, 0.01}).reused);
    test::writeProceduralVdb(path, "cloud", 32);
    EXPECT_FALSE(sharedOracleField(gradientAlpha(), {loadedVolume(path), 1.0, 3, 0.01}).reused);
}

// A volume not read from a file is known by its tree; the entry keeps the
// grid alive, so a later grid at the same address cannot be mistaken for it.
TEST(OracleCache, AProceduralVolumeIsKnownByItsTree) {
    clearOracleCache();
    const Scene a = loadScene("builtin:cloud"), b = loadScene("builtin:cloud");
    EXPECT_FALSE(sharedOracleField(gradientAlpha(), {a.volumes.front(), 1.0, 3, 0.01}).reused);
    EXPECT_TRUE(sharedOracleField(gradientAlpha(), {a.volumes.front(), 1.0, 3, 0.01}).reused);
    EXPECT_FALSE(sharedOracleField(gradientAlpha(), {b.volumes.front(), 1.0, 3, 0.01}).reused);
}

TEST(OracleCache, OnlyTheLastFieldsAreKept) {
    clearOracleCache();
    const Scene s = loadScene("builtin:cloud");
    const Volume& v = s.volumes.front();
    for (int k = 0; k <= kOracleCacheEntries; ++k) sharedOracleField(gradientAlpha(), {v, 1.0, 3, 0.01 * (k + 1)});
    EXPECT_TRUE(sharedOracleField(gradientAlpha(), {v, 1.0, 3, 0.01 * (kOracleCacheEntries + 1)}).reused);
    EXPECT_FALSE(sharedOracleField(gradientAlpha(), {v, 1.0, 3, 0.01}).reused);  // the oldest went
}

TEST(OracleCache, ARenderSaysWhetherItBuiltOrReusedAndTheImagesAgree) {
    clearOracleCache();
    test::TempDir dir;
    test::writeProceduralVdb(dir / "cloud.vdb", "cloud", 24);
    const std::string path = (dir / "cloud.vdb").string();
    const RenderOutcome built = test::render(path, "24x24", {}, "volume.adaptive3d");
    const RenderOutcome reused = test::render(path, "24x24", {}, "volume.adaptive3d");
    EXPECT_EQ(built.counters.at("oracle.built"), 1);
    EXPECT_EQ(built.counters.count("oracle.reused"), 0u);
    EXPECT_EQ(reused.counters.at("oracle.reused"), 1);
    EXPECT_EQ(reused.counters.count("oracle.built"), 0u);
    EXPECT_EQ(test::rmse(built.image, reused.image), 0.0);
    EXPECT_EQ(built.counters.at("volume.samples"), reused.counters.at("volume.samples"));
}
