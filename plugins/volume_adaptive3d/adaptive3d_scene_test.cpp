// volume.adaptive3d with meshes and the slice renderers with several
// volumes: rays end at surfaces without skipping past them, surfaces are lit
// and composited behind, overlapping volumes add their extinction.
#include <gtest/gtest.h>

#include <cmath>

#include "core/volume/optics/segment_tables.hpp"
#include "oracles/oracle.hpp"
#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;

namespace {

// The largest distance everywhere: every skip the pyramid allows.
const OracleRegistrar farOracle{{"test.far", "test: 2^lmax slices everywhere", [](const OracleContext& ctx) {
                                     OracleField f;
                                     f.constant = float((1 << ctx.lmax) * ctx.sliceSpacing);
                                     return f;
                                 }}};

// A quad facing +z at depth z, 4 x 4 wide, of albedo kd.
void writePlane(const test::TempDir& dir, double z, double kd) {
    const std::string k = std::to_string(kd), zs = std::to_string(z);
    test::writeText(dir / "plane.mtl", "newmtl m\nKd " + k + " " + k + " " + k + "\n");
    test::writeText(dir / "plane.obj", "mtllib plane.mtl\nusemtl m\nv -2 -2 " + zs + "\nv 2 -2 " + zs + "\nv 2 2 " + zs +
                                           "\nv -2 2 " + zs + "\nf 1 2 3 4\n");
}

// A 32^3 sphere (density 1 inside radius 0.4: 25.6 voxels across), white,
// extinction e at density 1, seen from z = eyeZ.
std::string sphereScene(double e, bool mesh, const std::string& lights, double eyeZ = 3) {
    return R"({"camera": {"eye": [0, 0, )" + std::to_string(eyeZ) + R"(], "target": [0, 0, -1], "up": [0, 1, 0], "fov": 30},
        "volumes": [{"procedural": "sphere", "resolution": 32, "transfer_function": {"points": [
            {"s": 0, "color": [1, 1, 1], "extinction": 0}, {"s": 1, "color": [1, 1, 1], "extinction": )" + std::to_string(e) + R"(}]}}],
        )" + std::string(mesh ? R"("meshes": [{"file": "plane.obj"}],)" : "") + R"( "lights": )" + lights + "}";
}

std::string combined(const char* name) { return std::string(WEFT_SOURCE_DIR) + "/scenes/combined/" + name; }

const char* kLight = R"([{"type": "directional", "direction": [0, 0, -1], "intensity": 2}])";

}  // namespace

TEST(Adaptive3dScene, WallBehindTheVolumeIsVisibleAndLit) {
    test::TempDir dir;
    writePlane(dir, -1.0, 0.5);
    test::writeText(dir / "s.json", sphereScene(0.04, true, kLight));
    const double T = std::exp(-0.04 * 25.6), plane = 0.5 / M_PI * 2.0;
    for (const char* oracle : {"oracle=gradient_alpha", "oracle=test.far"}) {
        const RenderOutcome out = test::render((dir / "s.json").string(), "33x33", {"spacing=0.25", oracle}, "volume.adaptive3d");
        EXPECT_NEAR(out.image.at(16, 16, 0), (1 - T) + T * plane, 8e-3) << oracle;
        EXPECT_NEAR(out.image.at(0, 0, 1), plane, 1e-5) << oracle;  // beside the sphere: the lit wall alone
        EXPECT_EQ(out.image.at(16, 16, 3), 1.0f);
        EXPECT_EQ(out.counters.at("rays.surface"), 33 * 33);
    }
}

TEST(Adaptive3dScene, WallInsideTheVolumeHidesWhatIsBehindIt) {
    // Eye and black wall both inside the sphere's uniform core, 0.4 apart:
    // the centre pixel sees 12.8 voxels of density 1, exactly, however far
    // the oracle lets it skip; without the wall it sees 19.2 voxels.
    test::TempDir dir;
    writePlane(dir, -0.2, 0.0);
    test::writeText(dir / "wall.json", sphereScene(0.05, true, "[]", 0.2));
    test::writeText(dir / "bare.json", sphereScene(0.05, false, "[]", 0.2));
    const double front = 1 - std::exp(-0.05 * 12.8);
    for (const char* oracle : {"oracle=gradient_alpha", "oracle=test.far", "oracle=minimum"})
        for (const std::string spacing : {"0.3", "1", "3"}) {
            const std::vector<std::string> sets = {"spacing=" + spacing, oracle};
            const RenderOutcome wall = test::render((dir / "wall.json").string(), "9x9", sets, "volume.adaptive3d");
            const RenderOutcome bare = test::render((dir / "bare.json").string(), "9x9", sets, "volume.adaptive3d");
            EXPECT_NEAR(wall.image.at(4, 4, 0), front, 2e-4) << oracle << " spacing " << spacing;
            EXPECT_EQ(wall.image.at(4, 4, 3), 1.0f);
            // What the wall hides (test.far skips the sphere's far edge, which only the bare render crosses).
            if (std::string(oracle) == "oracle=test.far") continue;
            EXPECT_GT(bare.image.at(4, 4, 0), front + 0.1) << oracle << " spacing " << spacing;
            for (int y = 0; y < 9; ++y)
                for (int x = 0; x < 9; ++x) ASSERT_LT(wall.image.at(x, y, 0), bare.image.at(x, y, 0)) << x << "," << y;
        }
}

TEST(Adaptive3dScene, MinimumOracleEqualsPreintWithMeshes) {
    // Every slice sampled: the same segments, the same cut, the same shading.
    const RenderOutcome pre = test::render(combined("ct_stent.json"), "48x36", {}, "volume.preint");
    const RenderOutcome ada = test::render(combined("ct_stent.json"), "48x36", {"oracle=minimum"}, "volume.adaptive3d");
    EXPECT_LT(test::rmse(pre.image, ada.image), 1e-6);
    EXPECT_EQ(pre.counters.at("rays.surface"), ada.counters.at("rays.surface"));
}

TEST(Adaptive3dScene, CtStentAgreesWithFineRaymarch) {
    const RenderOutcome ray = test::render(combined("ct_stent.json"), "64x48", {"step=0.1", "ert=1"}, "volume.raymarch");
    const RenderOutcome ada = test::render(combined("ct_stent.json"), "64x48", {}, "volume.adaptive3d");
    const RenderOutcome pre = test::render(combined("ct_stent.json"), "64x48", {}, "volume.preint");
    EXPECT_LT(test::rmse(ada.image, ray.image), 0.01);
    EXPECT_LT(test::rmse(pre.image, ray.image), 0.01);
    EXPECT_LT(ada.counters.at("volume.samples"), pre.counters.at("volume.samples"));  // it still skips
}

TEST(Adaptive3dScene, CombinedScenesAreTheSameForAnyThreadCount) {
    for (const char* scene : {"ct_stent.json", "two_volumes.json"}) {
        const RenderOutcome a = test::render(combined(scene), "61x45", {}, "volume.adaptive3d", 1);
        const RenderOutcome b = test::render(combined(scene), "61x45", {}, "volume.adaptive3d", 2);
        EXPECT_EQ(a.image.data(), b.image.data()) << scene;
        EXPECT_EQ(a.counters, b.counters) << scene;
        for (float v : a.image.data()) ASSERT_TRUE(std::isfinite(v)) << scene;
    }
}

TEST(Adaptive3dScene, SppAveragesTheSurfacesLightSamples) {
    // The Cornell box's area light: one light sample per pixel is noisy.
    // More samples come closer to a 256-sample render, and the volume pass
    // is the same whatever the spp (the smoke's pixels over no wall agree).
    const auto at = [](int spp) {
        return test::render(combined("smoke_in_cornell.json"), "32x32", {}, "volume.adaptive3d", 0, spp);
    };
    const RenderOutcome one = at(1), sixteen = at(16), ref = at(256);
    const double e1 = test::rmse(one.image, ref.image), e16 = test::rmse(sixteen.image, ref.image);
    EXPECT_LT(e16, 0.5 * e1);
    EXPECT_EQ(sixteen.counters.at("rays.surface"), 16 * one.counters.at("rays.surface"));
    EXPECT_EQ(sixteen.counters.at("volume.samples"), one.counters.at("volume.samples"));
    for (float v : ref.image.data()) ASSERT_TRUE(std::isfinite(v));
}

TEST(SliceVolumes, TwoOverlappingVolumesAgreeWithFineRaymarch) {
    const RenderOutcome ray = test::render(combined("two_volumes.json"), "64x48", {"step=0.1", "ert=1"}, "volume.raymarch");
    for (const char* technique : {"volume.preint", "volume.adaptive3d"}) {
        const RenderOutcome out = test::render(combined("two_volumes.json"), "64x48", {"spacing=0.5"}, technique);
        EXPECT_LT(test::rmse(out.image, ray.image), 6e-3) << technique;
    }
    const RenderOutcome a = test::render(combined("two_volumes.json"), "40x30", {}, "volume.preint", 1);
    const RenderOutcome b = test::render(combined("two_volumes.json"), "40x30", {}, "volume.preint", 2);
    EXPECT_EQ(a.image.data(), b.image.data());
}

namespace {

// The cloud with extinction e, once or as `copies` overlapping copies of
// extinction e / copies; `extra` appends another volume entry.
std::string cloudScene(int copies, double e, const std::string& extra = "") {
    std::string vols;
    for (int i = 0; i < copies; ++i)
        vols += std::string(i ? "," : "") + R"({"procedural": "cloud", "resolution": 32, "transfer_function": {"points": [
            {"s": 0, "color": [0.9, 0.6, 0.3], "extinction": 0}, {"s": 1, "color": [0.9, 0.6, 0.3], "extinction": )" +
                std::to_string(e / copies) + "}]}}";
    return R"({"camera": {"eye": [0, 0.2, 2.2], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 40}, "volumes": [)" + vols + extra + "]}";
}

}  // namespace

TEST(SliceVolumes, CopiesWithSplitExtinctionMatchOneVolume) {
    // Same colour: the combined segments are exact, so two copies of half the
    // extinction look like one (up to table interpolation).
    test::TempDir dir;
    test::writeText(dir / "one.json", cloudScene(1, 0.2));
    test::writeText(dir / "two.json", cloudScene(2, 0.2));
    for (const char* technique : {"volume.preint", "volume.adaptive3d"}) {
        const RenderOutcome one = test::render((dir / "one.json").string(), "40x30", {}, technique);
        const RenderOutcome two = test::render((dir / "two.json").string(), "40x30", {}, technique);
        EXPECT_LT(test::rmse(one.image, two.image), 2e-3) << technique;
        EXPECT_GT(test::rmse(one.image, Image::rgba(40, 30)), 0.02) << technique;  // not an empty image
    }
}

TEST(SliceVolumes, ATransparentSecondVolumeChangesNothing) {
    // The N-volume path with one volume that contributes: bit-identical.
    test::TempDir dir;
    const std::string clear = R"(, {"procedural": "sphere", "resolution": 16, "scale": 0.5, "rotate": [0, 30, 0],
        "transfer_function": {"points": [{"s": 0, "extinction": 0}, {"s": 1, "extinction": 0}]}})";
    test::writeText(dir / "one.json", cloudScene(1, 0.2));
    test::writeText(dir / "two.json", cloudScene(1, 0.2, clear));
    for (const auto& [technique, sets] : std::vector<std::pair<std::string, std::vector<std::string>>>{
             {"volume.preint", {}}, {"volume.adaptive3d", {"oracle=minimum"}}}) {
        const RenderOutcome one = test::render((dir / "one.json").string(), "40x30", sets, technique);
        const RenderOutcome two = test::render((dir / "two.json").string(), "40x30", sets, technique);
        EXPECT_EQ(one.image.data(), two.image.data()) << technique;
    }
}

TEST(SliceVolumes, CombineMediaIsExactForOneVolumeAndOneColour) {
    const PreintSample a{0.3f, 0.2f, 0.1f, 0.5f}, zero{0, 0, 0, 0};
    const PreintSample one[] = {zero, a, zero};
    const PreintSample c = combineMedia(one, 3);
    EXPECT_EQ(c.r, a.r);
    EXPECT_EQ(c.a, a.a);
    // Grey media of opacities 0.5 and 0.2 emitting colour 0.8 per unit opacity.
    const PreintSample grey[] = {{0.4f, 0.4f, 0.4f, 0.5f}, {0.16f, 0.16f, 0.16f, 0.2f}};
    const PreintSample g = combineMedia(grey, 2);
    EXPECT_NEAR(g.a, 1 - 0.5 * 0.8, 1e-6);
    EXPECT_NEAR(g.r, 0.8 * g.a, 1e-6);
}
