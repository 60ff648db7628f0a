// Colour (albedo) grids: which grid a volume reads (by role, by alias, from
// its own file, by a bare .vdb's conventional name), the errors, the tints
// (clamped, NaN untinted, resampled into the density's index space), and
// what they render: a slab tinted by c scatters exactly like the slab with
// scatter x c and absorb + scatter (1 - c), in volume.singlescatter and
// mesh.pathtrace; colour 1 changes nothing, colour 0 scatters nothing.
#include <gtest/gtest.h>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <limits>

#include "core/scene/scene.hpp"
#include "core/volume/volume_grids.hpp"
#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;

namespace {

constexpr double kVoxel = 0.05;

// A slab of density 1 (16 x 16 x 8 voxels) and, beside it in the file, a
// vec3s grid "Cd" of `color` over the slab and two voxels around it (so
// trilinear lookups anywhere the density is non-zero read the colour
// alone), a float grid "grey" of color[0] and an int32 grid "mask".
void writeTintedSlab(const std::filesystem::path& path, const openvdb::Vec3s& color, double colorVoxel = kVoxel) {
    initVdb();
    auto density = openvdb::FloatGrid::create(0.0f);
    density->setName("density");
    density->setTransform(openvdb::math::Transform::createLinearTransform(kVoxel));
    density->denseFill(openvdb::CoordBBox(openvdb::Coord(-8, -8, -4), openvdb::Coord(7, 7, 3)), 1.0f, true);
    const double k = kVoxel / colorVoxel;
    const openvdb::CoordBBox around(openvdb::Coord(int(std::floor(-10 * k)), int(std::floor(-10 * k)), int(std::floor(-6 * k))),
                                    openvdb::Coord(int(std::ceil(9 * k)), int(std::ceil(9 * k)), int(std::ceil(5 * k))));
    auto cd = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    cd->setName("Cd");
    cd->setTransform(openvdb::math::Transform::createLinearTransform(colorVoxel));
    cd->denseFill(around, color, true);
    auto grey = openvdb::FloatGrid::create(0.0f);
    grey->setName("grey");
    grey->setTransform(cd->transform().copy());
    grey->denseFill(around, color[0], true);
    auto mask = openvdb::Int32Grid::create(0);
    mask->setName("mask");
    mask->denseFill(around, 1, true);
    openvdb::io::File file(path.string());
    file.write({density, cd, grey, mask});
    file.close();
}

// A scene of the slab under a directional light, with its medium and `grids`.
std::string slabScene(const test::TempDir& dir, const std::string& name, const std::string& medium, const std::string& grids = "") {
    test::writeText(dir / name, R"({"camera": {"eye": [0.3, 0.4, 2], "target": [0, 0, 0], "fov": 30},
        "lights": [{"type": "directional", "direction": [0.3, -1, -0.5], "intensity": 3}],
        "volumes": [{"file": "slab.vdb", "medium": )" + medium + (grids.empty() ? "" : ", \"grids\": " + grids) + "}]}");
    return (dir / name).string();
}

Vec3d tintAt(const Volume& v, const openvdb::Coord& c) { return Vec3d(v.color->tree().getValue(c)); }

Image renderWith(const std::string& scene, const std::string& technique, const std::vector<std::string>& sets, int spp = 8) {
    return test::render(scene, "24x16", sets, technique, 0, spp).image;
}

struct Technique {
    std::string name;
    std::vector<std::string> sets;
};

const std::vector<Technique>& scatteringTechniques() {
    static const std::vector<Technique> t{{"volume.singlescatter", {}},
                                          {"volume.singlescatter", {"estimator=ratio"}},
                                          {"mesh.pathtrace", {"max_depth=3"}}};
    return t;
}

}  // namespace

TEST(VolumeColor, TheGridIsFoundByRoleAliasOwnFileAndConventionalName) {
    test::TempDir dir;
    writeTintedSlab(dir / "slab.vdb", {0.25f, 0.5f, 0.75f});
    const std::string medium = R"({"absorb": [0.1, 0.1, 0.1], "scatter": [1, 1, 1]})";
    for (const std::string grids : {R"({"color": "Cd"})", R"({"albedo": "Cd"})", R"({"color": {"file": "slab.vdb", "grid": "Cd"}})"}) {
        const Scene s = loadScene(slabScene(dir, "s.json", medium, grids));
        ASSERT_TRUE(s.volumes[0].color) << grids;
        EXPECT_NE(s.volumes[0].grids.find("color=Cd"), std::string::npos) << s.volumes[0].grids;
        const Vec3d t = tintAt(s.volumes[0], openvdb::Coord(0));
        EXPECT_EQ(t, Vec3d(0.25, 0.5, 0.75)) << grids;
        EXPECT_EQ(tintAt(s.volumes[0], openvdb::Coord(100)), Vec3d(1.0));  // outside: untinted
    }
    // A float grid is a grey tint.
    const Scene grey = loadScene(slabScene(dir, "s.json", medium, R"({"color": "grey"})"));
    EXPECT_EQ(tintAt(grey.volumes[0], openvdb::Coord(0)), Vec3d(0.25));
    // A bare .vdb: "Cd" by its conventional name.
    const Scene bare = loadScene((dir / "slab.vdb").string());
    ASSERT_TRUE(bare.volumes[0].color);
    EXPECT_TRUE(bare.volumes[0].gridsPicked);
    EXPECT_NE(bare.volumes[0].grids.find("color=Cd"), std::string::npos) << bare.volumes[0].grids;
}

TEST(VolumeColor, WrongGridsAreOneLineErrorsNamingThem) {
    test::TempDir dir;
    writeTintedSlab(dir / "slab.vdb", {0.5f, 0.5f, 0.5f});
    const std::string medium = R"({"absorb": [0.1, 0.1, 0.1], "scatter": [1, 1, 1]})";
    const auto errorWith = [&](const std::string& grids) { return test::errorOf([&] { loadScene(slabScene(dir, "s.json", medium, grids)); }); };
    const std::string wrongType = errorWith(R"({"color": "mask"})");
    EXPECT_NE(wrongType.find("the color grid 'mask' holds int32 values; color needs a vec3s or float grid"), std::string::npos) << wrongType;
    EXPECT_EQ(wrongType.find('\n'), std::string::npos);
    EXPECT_NE(errorWith(R"({"albedo": "nope"})").find("no grid named 'nope' for color"), std::string::npos);
    EXPECT_NE(errorWith(R"({"color": "Cd", "albedo": "Cd"})").find("names the color grid again"), std::string::npos);
    EXPECT_NE(errorWith(R"({"colour": "Cd"})").find("unknown key 'colour'"), std::string::npos);
}

// Clamped to [0, 1], NaN untinted, and a grid of its own voxel size
// resampled into the density's index space.
TEST(VolumeColor, TintsAreClampedAndResampled) {
    test::TempDir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    writeTintedSlab(dir / "slab.vdb", {2.0f, -1.0f, nan});
    const std::string medium = R"({"absorb": [0.1, 0.1, 0.1], "scatter": [1, 1, 1]})";
    const Scene s = loadScene(slabScene(dir, "s.json", medium, R"({"color": "Cd"})"));
    EXPECT_EQ(tintAt(s.volumes[0], openvdb::Coord(0)), Vec3d(1.0, 0.0, 1.0));
    writeTintedSlab(dir / "slab.vdb", {0.25f, 0.5f, 0.75f}, 2 * kVoxel);
    const Scene coarse = loadScene(slabScene(dir, "s.json", medium, R"({"color": "Cd"})"));
    const Volume& v = coarse.volumes[0];
    EXPECT_EQ(v.color->transform(), v.grid->transform());
    const Vec3d t = tintAt(v, openvdb::Coord(1, 2, 1));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], 0.25 * (c + 1), 1e-6);
}

// scatter' = scatter c, absorb' = absorb + scatter (1 - c): the same picture.
TEST(VolumeColor, ATintedSlabScattersLikeTheEquivalentUniformMedium) {
    test::TempDir dir;
    writeTintedSlab(dir / "slab.vdb", {0.25f, 0.5f, 0.75f});
    const std::string tinted = slabScene(dir, "tinted.json", R"({"absorb": [0.1, 0.2, 0.3], "scatter": [1, 2, 1]})", R"({"color": "Cd"})");
    const std::string uniform = slabScene(dir, "uniform.json", R"({"absorb": [0.85, 1.2, 0.55], "scatter": [0.25, 1, 0.75]})");
    for (const Technique& t : scatteringTechniques()) {
        const Image a = renderWith(tinted, t.name, t.sets), b = renderWith(uniform, t.name, t.sets);
        const double peak = test::peakColourOf(b);
        ASSERT_GT(peak, 0.01) << t.name;
        EXPECT_LT(compareImages(a, b).overall.maxAbs, 1e-4 * peak) << t.name << " " << (t.sets.empty() ? "" : t.sets[0]);
    }
}

// Colour 1 (and NaN, read as 1) is the untinted medium exactly; colour 0
// scatters nothing while the extinction, hence alpha, stays.
TEST(VolumeColor, ExtremeColoursRenderTheirLimits) {
    test::TempDir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::string medium = R"({"absorb": [0.1, 0.1, 0.1], "scatter": [1, 1, 1]})";
    writeTintedSlab(dir / "slab.vdb", {1, 1, 1});
    const std::string plain = slabScene(dir, "plain.json", medium), white = slabScene(dir, "white.json", medium, R"({"color": "Cd"})");
    for (const Technique& t : scatteringTechniques()) {
        const Image untinted = renderWith(plain, t.name, t.sets, 4);
        EXPECT_EQ(compareImages(renderWith(white, t.name, t.sets, 4), untinted).overall.maxAbs, 0.0) << t.name;
        writeTintedSlab(dir / "slab.vdb", {nan, nan, nan});
        const Image nanImage = renderWith(white, t.name, t.sets, 4);
        EXPECT_EQ(compareImages(nanImage, untinted).overall.maxAbs, 0.0) << t.name;
        writeTintedSlab(dir / "slab.vdb", {0, 0, 0});
        const Image black = renderWith(white, t.name, t.sets, 4);
        writeTintedSlab(dir / "slab.vdb", {1, 1, 1});
        ASSERT_GT(test::peakColourOf(untinted), 0.01) << t.name;
        EXPECT_EQ(test::peakColourOf(black), 0.0) << t.name;
        double alphaBlack = 0, alphaUntinted = 0;
        for (int y = 0; y < black.height(); ++y)
            for (int x = 0; x < black.width(); ++x) {
                for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(nanImage.at(x, y, c)));
                alphaBlack += black.at(x, y, 3), alphaUntinted += untinted.at(x, y, 3);
            }
        // singlescatter's alpha is its primary transmittance, the same numbers; the path tracer's an estimate of it.
        EXPECT_NEAR(alphaBlack, alphaUntinted, (t.name == "mesh.pathtrace" ? 0.05 : 1e-6) * alphaUntinted) << t.name;
    }
}

// A technique that does not scatter does not read the colour: a scene that
// names it is refused in one line; a bare .vdb's Cd, found by its name, is
// only reported.
TEST(VolumeColor, TechniquesThatDoNotScatterRefuseANamedColourGrid) {
    test::TempDir dir;
    writeTintedSlab(dir / "slab.vdb", {0.5f, 0.5f, 0.5f});
    const std::string scene = slabScene(dir, "s.json", R"({"absorb": [0.1, 0.1, 0.1], "scatter": [1, 1, 1]})", R"({"color": "Cd"})");
    for (const char* t : {"volume.raymarch", "volume.preint", "volume.adaptive3d"}) {
        const std::string e = test::errorOf([&] { test::render(scene, "8x8", {}, t); });
        EXPECT_NE(e.find(std::string(t) + " does not scatter light, so it would not use the colour grid"), std::string::npos) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
    const Scene bare = loadScene((dir / "slab.vdb").string());
    EXPECT_EQ(unusedColorGrids(bare, "volume.raymarch"), "volume.raymarch does not scatter light: the colour grid of '" +
                                                             (dir / "slab.vdb").string() + "' is not used");
    EXPECT_NO_THROW(test::render((dir / "slab.vdb").string(), "8x8", {}, "volume.raymarch"));
}
