// volume.preint with meshes: rays end at the first surface, the cut segment
// integrated with its true length, the surface composited behind the volume.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;

namespace {

// A quad facing +z at depth z, 4 x 4 wide, of albedo kd.
void writePlane(const test::TempDir& dir, double z, double kd) {
    const std::string k = std::to_string(kd), zs = std::to_string(z);
    test::writeText(dir / "plane.mtl", "newmtl m\nKd " + k + " " + k + " " + k + "\n");
    test::writeText(dir / "plane.obj", "mtllib plane.mtl\nusemtl m\nv -2 -2 " + zs + "\nv 2 -2 " + zs + "\nv 2 2 " + zs +
                                           "\nv -2 2 " + zs + "\nf 1 2 3 4\n");
}

// A 32^3 sphere (density 1 inside radius 0.4), white, extinction e at density 1.
std::string sphereScene(double eyeZ, double e, const std::string& lights) {
    return R"({"camera": {"eye": [0, 0, )" + std::to_string(eyeZ) + R"(], "target": [0, 0, -1], "up": [0, 1, 0], "fov": 30},
        "volumes": [{"procedural": "sphere", "resolution": 32, "transfer_function": {"points": [
            {"s": 0, "color": [1, 1, 1], "extinction": 0}, {"s": 1, "color": [1, 1, 1], "extinction": )" + std::to_string(e) + R"(}]}}],
        "meshes": [{"file": "plane.obj"}], "lights": )" + lights + "}";
}

}  // namespace

TEST(PreintScene, SurfaceInsideTheVolumeCutsTheLastSegmentAtItsTrueLength) {
    // Eye and black plane both inside the sphere, 0.4 apart: 12.8 voxels of density 1.
    test::TempDir dir;
    writePlane(dir, -0.2, 0.0);
    test::writeText(dir / "s.json", sphereScene(0.2, 0.05, "[]"));
    const double expected = 1 - std::exp(-0.05 * 12.8);
    for (const std::string spacing : {"0.3", "0.7", "3", "64"}) {
        const RenderOutcome out = test::render((dir / "s.json").string(), "9x9", {"spacing=" + spacing}, "volume.preint");
        EXPECT_NEAR(out.image.at(4, 4, 0), expected, 2e-4) << "spacing " << spacing;
        EXPECT_EQ(out.image.at(4, 4, 3), 1.0f);
    }
}

TEST(PreintScene, DiffusePlaneBehindTheSphereShowsThroughItsTransmittance) {
    test::TempDir dir;
    writePlane(dir, -1.0, 0.5);
    test::writeText(dir / "s.json", sphereScene(3.0, 0.04, R"([{"type": "directional", "direction": [0, 0, -1], "intensity": 2}])"));
    const RenderOutcome out = test::render((dir / "s.json").string(), "33x33", {"spacing=0.25"}, "volume.preint");
    const double T = std::exp(-0.04 * 25.6), plane = 0.5 / M_PI * 2.0;
    EXPECT_NEAR(out.image.at(16, 16, 0), (1 - T) + T * plane, 8e-3);
    EXPECT_NEAR(out.image.at(0, 0, 1), plane, 1e-5);
    EXPECT_EQ(out.counters.at("rays.surface"), 33 * 33);
}

TEST(PreintScene, CombinedSceneIsTheSameForAnyThreadCount) {
    const std::string scene = std::string(WEFT_SOURCE_DIR) + "/scenes/combined/smoke_over_ground.json";
    const RenderOutcome a = test::render(scene, "64x48", {}, "volume.preint", 1);
    const RenderOutcome b = test::render(scene, "64x48", {}, "volume.preint", 2);
    EXPECT_EQ(a.image.data(), b.image.data());
    for (float v : a.image.data()) ASSERT_TRUE(std::isfinite(v));
}
