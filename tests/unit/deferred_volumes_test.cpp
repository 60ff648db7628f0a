// lighting.vpl_deferred and lighting.adaptive_indirect with volumes: a
// homogeneous slab in front of a lit wall dims it by exp(-sigma_t d), on the
// camera ray and on the shadow ray, a pixel that sees only the slab gets
// alpha 1 - T and no colour (nothing scatters in), smoke in the Cornell box
// changes the image and is the same on one and two threads, and a scene
// without volumes builds and counts nothing of them.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/vdb_fixtures.hpp"

using namespace weft;

namespace {

const char* kTechniques[] = {"lighting.vpl_deferred", "lighting.adaptive_indirect"};

// Per voxel length per unit density; the slab is kSlabVoxels thick.
const double kAbsorb[3] = {0.03, 0.05, 0.08};
const double kScatter = 0.02;
const int kSlabVoxels = 16;

double opticalDepth(int c) { return (kAbsorb[c] + kScatter) * kSlabVoxels; }

// A wall at z = -1 (x in [-2, 2], y in [-2, 0.1], Kd 0.5) seen by a camera
// on the z axis (5 x 5 pixels, 10 degrees: the top two rows miss the wall),
// a point light on the axis at lightZ, and, with `slab`, 16 voxels of 1/32
// filling z in [0, 0.5] in front of it, its coefficients times `scale`.
std::string wallScene(const test::TempDir& dir, const std::string& name, bool slab, double lightZ, double scale = 1) {
    test::writeText(dir.path() / "wall.mtl", "newmtl m\nKd 0.5 0.5 0.5\n");
    test::writeText(dir.path() / "wall.obj", "mtllib wall.mtl\nusemtl m\nv -2 -2 -1\nv 2 -2 -1\nv 2 0.1 -1\nv -2 0.1 -1\nf 1 2 3 4\n");
    std::string volumes;
    if (slab) {
        test::writeSlabVdb(dir.path() / "slab.vdb", 64, kSlabVoxels, 1.0 / 32);
        auto list = [&](double a, double b, double c) {
            return "[" + std::to_string(a * scale) + ", " + std::to_string(b * scale) + ", " + std::to_string(c * scale) + "]";
        };
        volumes = R"(, "volumes": [{"file": "slab.vdb", "medium": {"absorb": )" + list(kAbsorb[0], kAbsorb[1], kAbsorb[2]) +
                  R"(, "scatter": )" + list(kScatter, kScatter, kScatter) + "}}]";
    }
    const std::string text = R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 10},
        "meshes": [{"file": "wall.obj"}], "lights": [{"type": "point", "position": [0, 0, )" +
                             std::to_string(lightZ) + R"(], "intensity": 1}])" + volumes + "}";
    test::writeText(dir.path() / name, text);
    return (dir.path() / name).string();
}

RenderOutcome renderWith(const std::string& scene, const std::string& technique, int threads, std::vector<std::string> sets = {},
                         const std::string& res = "5x5") {
    RenderRequest r;
    r.input = scene, r.resolution = parseResolution(res), r.technique = technique, r.threads = threads, r.sets = std::move(sets);
    return renderToImage(r);
}

std::int64_t counter(const RenderOutcome& out, const std::string& name) {
    const auto it = out.counters.find(name);
    return it == out.counters.end() ? -1 : it->second;
}

}  // namespace

// The centre pixel's ray runs along z through the slab's middle, where the
// density is 1 except for the one-voxel ramps past the faces, which add two
// halves: the optical depth is sigma_t x 16 voxels. The march is exact on
// such a line (constant and linear stretches), so the tolerance, 1e-4
// relative, only covers float rounding.
TEST(DeferredVolumes, SlabDimsTheWallByItsTransmittanceOnTheCameraRay) {
    test::TempDir dir;
    const std::string clear = wallScene(dir, "clear.json", false, -0.5), smoke = wallScene(dir, "smoke.json", true, -0.5);
    for (const char* technique : kTechniques) {
        const Image a = renderWith(clear, technique, 0).image, b = renderWith(smoke, technique, 0).image;
        EXPECT_GT(a.at(2, 2, 0), 0.1f) << technique;  // about kd / pi x intensity / 0.5^2
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(b.at(2, 2, c) / a.at(2, 2, c), std::exp(-opticalDepth(c)), 1e-4 * std::exp(-opticalDepth(c)))
                << technique << " channel " << c;
        EXPECT_EQ(b.at(2, 2, 3), 1.0f) << technique;
    }
}

// The light in front of the slab: the shadow ray from the wall's centre
// crosses it along z as well, so the pixel carries T twice.
TEST(DeferredVolumes, SlabDimsTheShadowRayToo) {
    test::TempDir dir;
    const std::string clear = wallScene(dir, "clear.json", false, 1.5), smoke = wallScene(dir, "smoke.json", true, 1.5);
    for (const char* technique : kTechniques) {
        const Image a = renderWith(clear, technique, 0).image, b = renderWith(smoke, technique, 0).image;
        EXPECT_GT(a.at(2, 2, 0), 0.005f) << technique;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(b.at(2, 2, c) / a.at(2, 2, c), std::exp(-2 * opticalDepth(c)), 1e-4 * std::exp(-2 * opticalDepth(c)))
                << technique << " channel " << c;
    }
}

// The top row's centre pixel sees no surface: its ray crosses the slab at
// an angle (tan = 0.8 tan 5 degrees), so alpha = 1 - mean_c exp(-tau_c / cos).
// Fine steps (0.1 voxel) keep the march error on the slanted ramps below
// 1e-5; tolerance 1e-4.
TEST(DeferredVolumes, APixelThatSeesOnlyTheSlabHasItsOpacityAsAlphaAndNoColour) {
    test::TempDir dir;
    const std::string clear = wallScene(dir, "clear.json", false, -0.5), smoke = wallScene(dir, "smoke.json", true, -0.5);
    const double tanY = 0.8 * std::tan(5 * M_PI / 180), secant = std::sqrt(1 + tanY * tanY);
    double T = 0;
    for (int c = 0; c < 3; ++c) T += std::exp(-opticalDepth(c) * secant) / 3;
    for (const char* technique : kTechniques) {
        const Image a = renderWith(clear, technique, 0).image, b = renderWith(smoke, technique, 0, {"volume_step=0.1"}).image;
        EXPECT_EQ(a.at(2, 0, 3), 0.0f) << technique;
        EXPECT_NEAR(b.at(2, 0, 3), 1 - T, 1e-4) << technique;
        for (int c = 0; c < 3; ++c) EXPECT_EQ(b.at(2, 0, c), 0.0f) << technique;
    }
}

TEST(DeferredVolumes, SmokeInTheCornellBoxDarkensItTheSameOnOneAndTwoThreads) {
    const std::string root = WEFT_SOURCE_DIR;
    for (const char* technique : kTechniques) {
        const RenderOutcome box = renderWith(root + "/scenes/cornell.json", technique, 2, {}, "24x24");
        const RenderOutcome one = renderWith(root + "/scenes/combined/smoke_in_cornell.json", technique, 1, {}, "24x24");
        const RenderOutcome two = renderWith(root + "/scenes/combined/smoke_in_cornell.json", technique, 2, {}, "24x24");
        EXPECT_EQ(one.image.data(), two.image.data()) << technique;
        int darker = 0;
        double sumBox = 0, sumSmoke = 0;
        for (int y = 0; y < 24; ++y)
            for (int x = 0; x < 24; ++x) {
                const float b = box.image.at(x, y, 0), s = one.image.at(x, y, 0);
                ASSERT_TRUE(std::isfinite(s)) << technique;
                darker += s < 0.98f * b;
                sumBox += b, sumSmoke += s;
            }
        EXPECT_GT(darker, 24 * 24 / 20) << technique;  // the cloud and its shadows
        EXPECT_LT(sumSmoke, 0.99 * sumBox) << technique;
        EXPECT_GT(counter(one, "volume.transmittance"), 24 * 24) << technique;  // camera rays and more
        EXPECT_GT(counter(one, "volume.lookups"), counter(one, "volume.transmittance")) << technique;
        EXPECT_EQ(counter(one, "volume.lookups"), counter(two, "volume.lookups")) << technique;
        EXPECT_EQ(counter(box, "volume.transmittance"), -1) << technique;  // nothing of volumes without one
        EXPECT_EQ(counter(box, "volume.lookups"), -1) << technique;
    }
}

// Volumes whose medium cannot attenuate (zero coefficients) build nothing
// either: the image is the mesh scene's (up to the ray offsets, which
// scale with the scene's bounds, the volume's included: 1e-4 relative).
TEST(DeferredVolumes, AVolumeThatAbsorbsNothingLeavesTheImageAlone) {
    test::TempDir dir;
    const std::string clear = wallScene(dir, "clear.json", false, 1.5), none = wallScene(dir, "none.json", true, 1.5, 0.0);
    for (const char* technique : kTechniques) {
        const RenderOutcome a = renderWith(clear, technique, 0), b = renderWith(none, technique, 0);
        for (std::size_t i = 0; i < a.image.data().size(); ++i)
            ASSERT_NEAR(b.image.data()[i], a.image.data()[i], 1e-4 * std::abs(a.image.data()[i])) << technique << " " << i;
        EXPECT_EQ(counter(b, "volume.transmittance"), -1) << technique;
    }
}
