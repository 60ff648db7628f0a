#pragma once
// The cases of the extremes suite (tests/extremes/extremes_test.cpp): each
// writes its files into the case's folder and says what it changes.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/extremes/extreme_case.hpp"
#include "tests/support/vdb_fixtures.hpp"

namespace weft::test::extremes {

// Techniques whose volumes are coloured by the transfer function (emission
// and absorption); the others read density through the volume's medium.
inline bool usesTransferFunction(const std::string& technique) {
    return technique == "volume.raymarch" || technique == "volume.preint" || technique == "volume.adaptive3d";
}

inline float rgbaMax(const Image& image) {
    float m = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            for (int c = 0; c < 4; ++c) m = std::max(m, std::abs(image.at(x, y, c)));
    return m;
}

inline void expectTransparent(const std::string& technique, const Image& image) {
    EXPECT_EQ(rgbaMax(image), 0.0f) << technique << ": expected a fully transparent image";
}

// One volume file under a directional light, framed by the loader.
inline void volumeScene(CaseSetup& s, const std::string& file, json extra = json::object()) {
    json v = {{"file", file}};
    v.update(extra);
    s.scene["volumes"] = json::array({v});
    s.scene["lights"] = json::array({directionalLight()});
}

inline std::string ramp8(CaseSetup& s) {
    writeGrid(s.dir / "ramp.vdb", 8, [](int i, int j, int k) { return float(1 + i + j + k) / 22.0f; });
    return "ramp.vdb";
}

// A ground quad and a cube of meshes, a point and a directional light.
inline void meshScene(CaseSetup& s, double lightIntensity = 1.0) {
    writeText(s.dir / "ground.obj", groundObj(2.0, -0.5));
    writeText(s.dir / "cube.obj", cubeObj(0.3));
    s.scene["meshes"] = json::array({{{"file", "ground.obj"}}, {{"file", "cube.obj"}, {"translate", {0.4, -0.2, 0.0}}}});
    s.scene["lights"] = json::array({pointLight({0.0, 2.0, 1.0}, std::min(5.0 * lightIntensity, 1e30)), directionalLight(lightIntensity)});
    s.scene["camera"] = camera({0.0, 1.0, 3.0}, {0.0, -0.2, 0.0});
}

// The mesh scene with a cube of smoke above the ground.
inline void mixedScene(CaseSetup& s, double lightIntensity = 1.0) {
    meshScene(s, lightIntensity);
    writeGrid(s.dir / "smoke.vdb", 8, [](int i, int j, int k) { return float((i + 2 * j + 3 * k) % 5) / 4.0f; });
    s.scene["volumes"] = json::array({{{"file", "smoke.vdb"}, {"translate", {-0.6, -0.4, -0.5}}}});
}

// A slab of density 1, 4 voxels of 0.25 thick along z, x and y in [-2, 2),
// seen along z through its middle: transmittance exp(-sigma * 4) with sigma
// per voxel length (the medium's absorb, the transfer function's extinction).
inline void slabScene(CaseSetup& s, double sigma) {
    writeSlabVdb(s.dir / "slab.vdb", 16, 4, 0.25);
    const json tf = {{"range", {0, 1}},
                     {"points", {{{"s", 0}, {"color", {0, 0, 0}}, {"extinction", 0}}, {{"s", 1}, {"color", {0, 0, 0}}, {"extinction", sigma}}}}};
    volumeScene(s, "slab.vdb", {{"transfer_function", tf}, {"medium", {{"absorb", {sigma, sigma, sigma}}, {"scatter", {0, 0, 0}}}}});
    s.scene["camera"] = camera({0.0, 0.0, -10.0}, {0.0, 0.0, 1.0}, 0.5);
    s.resolution = "1x1";
    s.spp = 1024;  // the path tracer's alpha is a mean of 0s and 1s
    const double alpha = 1.0 - std::exp(-4.0 * sigma);
    s.closedForm = [alpha](const std::string& technique, const Image& image) {
        const double tolerance = 0.01 + 5.0 * std::sqrt(alpha * (1 - alpha) / 1024);
        EXPECT_NEAR(image.at(0, 0, 3), alpha, tolerance) << technique << ": slab alpha 1 - exp(-sigma L)";
        EXPECT_LE(rgbaMax(image), 1.0f + 1e-4f) << technique;
    };
}

inline json flatTf(double extinction, double color) {
    return {{"range", {0, 1}},
            {"points", {{{"s", 0}, {"color", {color, color, color}}, {"extinction", extinction}},
                        {{"s", 1}, {"color", {color, color, color}}, {"extinction", extinction}}}}};
}

// Opaque where rays cross the cube (centre pixels), for the transfer-function techniques.
inline void expectOpaqueCentre(const std::string& technique, const Image& image) {
    if (!usesTransferFunction(technique)) return;
    EXPECT_NEAR(image.at(2, 2, 3), 1.0f, 1e-3f) << technique << ": alpha through an opaque cube";
    EXPECT_LE(rgbaMax(image), 1.0f + 1e-4f) << technique << ": premultiplied colour above alpha";
}

// Rotated and sheared index-to-world maps (OpenVDB's row-vector matrices).
inline openvdb::math::Mat4d rotatedMap() {
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.preScale(openvdb::math::Vec3d(0.125));
    m.postRotate(openvdb::math::X_AXIS, 0.5), m.postRotate(openvdb::math::Y_AXIS, 0.8), m.postRotate(openvdb::math::Z_AXIS, 1.1);
    return m;
}

inline openvdb::math::Mat4d shearedMap() {
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.preScale(openvdb::math::Vec3d(0.125));
    m.postShear(openvdb::math::X_AXIS, openvdb::math::Y_AXIS, 0.6);
    return m;
}

inline const std::vector<ExtremeCase>& extremeCases() {
    static const std::vector<ExtremeCase> cases = {
        {"empty_grid", [](CaseSetup& s) {
             writeEmptyVdb(s.dir / "empty.vdb");
             volumeScene(s, "empty.vdb");
             s.closedForm = expectTransparent;
         }},
        {"empty_scene", [](CaseSetup& s) {
             s.scene["lights"] = json::array({directionalLight()});
             s.scene["camera"] = camera({0, 0, 3}, {0, 0, 0});
             s.closedForm = expectTransparent;
         }},
        {"one_active_voxel", [](CaseSetup& s) {
             writeGrid(s.dir / "one.vdb", 8, [](int i, int j, int k) { return i == 3 && j == 4 && k == 5 ? 1.0f : 0.0f; });
             volumeScene(s, "one.vdb");
         }},
        {"constant_grid", [](CaseSetup& s) {
             writeConstantGrid(s.dir / "const.vdb", 8, 1.0f);
             volumeScene(s, "const.vdb");
         }},
        {"density_1e-8", [](CaseSetup& s) {
             writeConstantGrid(s.dir / "thin.vdb", 8, 1e-8f);
             volumeScene(s, "thin.vdb", {{"transfer_function", {{"range", {0, 1}}, {"points", {{{"s", 0}, {"extinction", 0}}, {{"s", 1}, {"extinction", 1}}}}}}});
             s.closedForm = [](const std::string& technique, const Image& image) {
                 for (int y = 0; y < image.height(); ++y)
                     for (int x = 0; x < image.width(); ++x) EXPECT_LE(image.at(x, y, 3), 1e-4f) << technique << ": alpha of a 1e-8 density";
             };
         }},
        {"density_1e8", [](CaseSetup& s) {
             // Dense voxels beside empty ones: bricks whose majorant is far above most of their voxels.
             writeGrid(s.dir / "dense.vdb", 8, [](int i, int j, int k) { return (i + j + k) % 2 ? 1e8f : 0.0f; });
             volumeScene(s, "dense.vdb");
         }},
        {"nan_inf_voxels", [](CaseSetup& s) {
             writeGrid(s.dir / "bad.vdb", 8, [](int i, int j, int k) {
                 const int n = i * 64 + j * 8 + k;
                 return n % 7 == 0 ? kNaN : n % 11 == 0 ? kInf : n % 13 == 0 ? -kInf : 0.5f;
             });
             volumeScene(s, "bad.vdb");
         }},
        {"tf_all_zero", [](CaseSetup& s) {
             writeConstantGrid(s.dir / "const.vdb", 8, 1.0f);
             volumeScene(s, "const.vdb", {{"transfer_function", flatTf(0, 0)}});
             s.closedForm = [](const std::string& technique, const Image& image) {
                 if (usesTransferFunction(technique)) expectTransparent(technique, image);
             };
         }},
        {"tf_all_opaque", [](CaseSetup& s) {
             writeConstantGrid(s.dir / "const.vdb", 8, 1.0f);
             volumeScene(s, "const.vdb", {{"transfer_function", flatTf(1e30, 1)}});
             s.mayRefuseNaming = {"transparent at the grid's background value"};  // the slicing techniques need it
             s.closedForm = expectOpaqueCentre;
         }},
        {"tf_opaque_above_background", [](CaseSetup& s) {
             writeConstantGrid(s.dir / "const.vdb", 8, 1.0f);
             const json tf = {{"range", {0, 1}},
                              {"points", {{{"s", 0}, {"extinction", 0}}, {{"s", 1e-3}, {"extinction", 1e30}}, {{"s", 1}, {"extinction", 1e30}}}}};
             volumeScene(s, "const.vdb", {{"transfer_function", tf}});
             s.closedForm = expectOpaqueCentre;
         }},
        {"slab_transmittance", [](CaseSetup& s) { slabScene(s, 0.25); }},
        {"step_min", [](CaseSetup& s) {
             mixedScene(s);
             s.extremes = {{"step", 1e-4}, {"spacing", 1e-4}, {"volume_step", 1e-4}};
             s.parametersOnly = true;
         }},
        {"step_max", [](CaseSetup& s) {
             mixedScene(s);
             s.extremes = {{"step", 1e4}, {"spacing", 1e4}, {"volume_step", 1e4}};
             s.parametersOnly = true;
         }},
        {"lmax_0", [](CaseSetup& s) {
             volumeScene(s, ramp8(s));
             s.extremes = {{"lmax", 0}};
             s.parametersOnly = true;
         }},
        {"lmax_max", [](CaseSetup& s) {
             volumeScene(s, ramp8(s));
             s.extremes = {{"lmax", 1e9}};
             s.parametersOnly = true;
         }},
        {"image_1x1", [](CaseSetup& s) {
             mixedScene(s);
             s.resolution = "1x1";
         }},
        {"image_1x4096", [](CaseSetup& s) {
             mixedScene(s);
             s.resolution = "1x4096";
         }},
        {"image_4096x1", [](CaseSetup& s) {
             mixedScene(s);
             s.resolution = "4096x1";
         }},
        {"spp_4096", [](CaseSetup& s) {
             mixedScene(s);
             s.resolution = "1x1";
             s.spp = 4096;
         }},
        {"vpls_1", [](CaseSetup& s) {
             meshScene(s);
             s.extremes = {{"vpls", 1}};
             s.sets = {{"interleave", "1x1"}};
             s.parametersOnly = true;
         }},
        {"vpls_1e5", [](CaseSetup& s) {
             meshScene(s);
             s.extremes = {{"vpls", 1e5}};
             s.parametersOnly = true;
         }},
        {"budget_below_minimum", [](CaseSetup& s) {
             meshScene(s);
             s.resolution = "8x8";
             s.extremes = {{"min_samples", 1e12}, {"batch", 1}};
             s.parametersOnly = true;
         }},
        {"all_zero_importance", [](CaseSetup& s) {
             writeText(s.dir / "ground.obj", groundObj(50.0, -1.0));
             s.scene["meshes"] = json::array({{{"file", "ground.obj"}}});
             s.scene["lights"] = json::array({directionalLight()});
             s.scene["camera"] = {{"eye", {0, 5, 0}}, {"target", {0, -1, 0}}, {"up", {0, 0, 1}}};
             s.extremes = {{"sigma_normal", 0}, {"sigma_position", 0}};
             s.parametersOnly = true;
         }},
        {"degenerate_triangles", [](CaseSetup& s) {
             meshScene(s);
             // Coincident corners, collinear corners and a sliver, some of them emissive.
             writeText(s.dir / "glow.mtl", "newmtl glow\nKd 0.5 0.5 0.5\nKe 4 4 4\n");
             writeText(s.dir / "degenerate.obj", "mtllib glow.mtl\nusemtl glow\nv 0 0 0\nv 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1e-30 0\n"
                                                 "f 1 2 3\nf 1 3 4\nf 1 3 5\nf 1 1 1\n");
             s.scene["meshes"].push_back({{"file", "degenerate.obj"}});
         }},
        {"zero_area_emitters_only", [](CaseSetup& s) {
             writeText(s.dir / "glow.mtl", "newmtl glow\nKd 0.5 0.5 0.5\nKe 4 4 4\n");
             writeText(s.dir / "flat.obj", "mtllib glow.mtl\nusemtl glow\nv 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 4 4 4\n");
             s.scene["meshes"] = json::array({{{"file", "flat.obj"}}});
             s.scene["camera"] = camera({0.5, 0.5, 3}, {0.5, 0.5, 0});
         }},
        {"camera_inside_volume", [](CaseSetup& s) {
             writeConstantGrid(s.dir / "const.vdb", 8, 1.0f);
             volumeScene(s, "const.vdb");
             s.scene["camera"] = camera({0.5, 0.5, 0.5}, {0.5, 0.5, 2.0}, 90);
         }},
        {"camera_inside_mesh", [](CaseSetup& s) {
             writeText(s.dir / "room.obj", cubeObj(1.0));
             s.scene["meshes"] = json::array({{{"file", "room.obj"}}});
             s.scene["lights"] = json::array({pointLight({0.0, 0.5, 0.0}, 1.0)});
             s.scene["camera"] = camera({0, 0, 0}, {0, 0, 1}, 120);
         }},
        {"lights_zero", [](CaseSetup& s) { mixedScene(s, 0.0); }},
        {"lights_1e30", [](CaseSetup& s) { mixedScene(s, 1e30); }},
        {"anisotropic_grid", [](CaseSetup& s) {
             // vdb_render's failing case: voxels of 0.133 x 0.133 x 0.132.
             openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
             m.preScale(openvdb::math::Vec3d(0.133, 0.133, 0.132));
             writeGrid(s.dir / "aniso.vdb", 8, [](int i, int j, int k) { return float((i + j + k) % 4) / 3.0f; }, affine(m));
             volumeScene(s, "aniso.vdb", {{"scale", {1.0, 0.25, 3.0}}});
         }},
        {"rotated_grid", [](CaseSetup& s) {
             writeGrid(s.dir / "rot.vdb", 8, [](int i, int j, int k) { return float((i + j + k) % 4) / 3.0f; }, affine(rotatedMap()));
             volumeScene(s, "rot.vdb", {{"rotate", {20, 30, 40}}});
         }},
        {"sheared_grid", [](CaseSetup& s) {
             writeGrid(s.dir / "shear.vdb", 8, [](int i, int j, int k) { return float((i + j + k) % 4) / 3.0f; }, affine(shearedMap()));
             volumeScene(s, "shear.vdb");
         }},
        {"obj_inf_vertex", [](CaseSetup& s) {
             writeText(s.dir / "inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n");
             s.input = (s.dir / "inf.obj").string();
             s.mustRefuseWith = "finite";
         }},
        {"obj_inf_vertex_in_scene", [](CaseSetup& s) {
             meshScene(s);
             writeText(s.dir / "inf.obj", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n");
             s.scene["meshes"].push_back({{"file", "inf.obj"}});
             s.mustRefuseWith = "finite";
         }},
    };
    return cases;
}

}  // namespace weft::test::extremes
