// Mesh loading: OBJ (+MTL, negative indices, CRLF), PLY (ASCII and binary)
// and Catmull-Clark subdivision with creases; bad files are one-line errors.
#include <gtest/gtest.h>

#include <fstream>

#include "core/lighting/emitters.hpp"
#include "core/base/error.hpp"
#include "core/mesh/mesh.hpp"
#include "core/scene/scene.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;

namespace {

const std::string kData = std::string(WEFT_SOURCE_DIR) + "/data/";

std::string errorOf(const std::function<void()>& fn) {
    try {
        fn();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

float distanceToNearestVertex(const TriangleMesh& mesh, const Vec3f& p) {
    float best = 1e30f;
    for (const Vec3f& v : mesh.positions) best = std::min(best, (v - p).length());
    return best;
}

}  // namespace

TEST(MeshLoading, CornellBoxObjHasItsQuadsMaterialsAndLight) {
    const PolyMesh poly = readPolyMesh(kData + "cornell/CornellBox-Original.obj");
    EXPECT_EQ(poly.faceCount(), 18);
    const TriangleMesh tri = triangulate(poly, "cornell");
    EXPECT_EQ(tri.triangleCount(), 36u);
    int emissive = 0;
    for (std::uint32_t m : tri.material) emissive += tri.materials[m].emissive() ? 1 : 0;
    EXPECT_EQ(emissive, 2);  // the light quad
    const Material& light = tri.materials[tri.material[35]];
    EXPECT_EQ(light.name, "light");
    EXPECT_FLOAT_EQ(light.emission.x(), 17.0f);
    const Material& left = tri.materials[tri.material[8]];
    EXPECT_EQ(left.name, "leftWall");
    EXPECT_NEAR(left.diffuse.y(), 0.065f, 1e-6f);
}

TEST(MeshLoading, EmittersFaceIntoTheBox) {
    Scene scene;
    scene.addMesh(triangulate(readPolyMesh(kData + "cornell/CornellBox-Original.obj"), "cornell"));
    const Emitters& e = scene.emitters();
    EXPECT_EQ(e.triangleCount(), 2u);
    const EmitterSample s = e.sample(0.3f, 0.5f, 0.5f);
    EXPECT_LT(s.normal.y(), -0.99f);  // the light shines down
    EXPECT_NEAR(s.position.y(), 1.98f, 1e-5f);
    // Uniform by area over the whole light: pdf = 1 / area.
    EXPECT_NEAR(s.pdfArea, 1.0f / (0.47f * 0.38f), 1e-2f);
}

TEST(MeshLoading, PlyAsciiAndBinaryGiveTheSameTriangles) {
    test::TempDir dir;
    const std::string header = "ply\nformat %s 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                               "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
    auto head = [&](const char* fmt) { char buf[512]; std::snprintf(buf, sizeof buf, header.c_str(), fmt); return std::string(buf); };
    test::writeText(dir / "a.ply", head("ascii") + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 2 2\n4 0 1 2 3\n3 1 4 2\n");
    {
        std::ofstream os(dir / "b.ply", std::ios::binary);
        os << head("binary_little_endian");
        const float v[15] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 2, 2};
        os.write(reinterpret_cast<const char*>(v), sizeof v);
        const unsigned char four = 4, three = 3;
        const int q[4] = {0, 1, 2, 3}, t[3] = {1, 4, 2};
        os.write(reinterpret_cast<const char*>(&four), 1), os.write(reinterpret_cast<const char*>(q), sizeof q);
        os.write(reinterpret_cast<const char*>(&three), 1), os.write(reinterpret_cast<const char*>(t), sizeof t);
    }
    for (const char* name : {"a.ply", "b.ply"}) {
        const TriangleMesh m = triangulate(readPolyMesh((dir / name).string()), name);
        EXPECT_EQ(m.triangleCount(), 3u) << name;
        EXPECT_EQ(m.positions.size(), 5u) << name;
        const BBoxd box = m.bounds();
        EXPECT_NEAR(box.max().z(), 2.0, 1e-9) << name;
    }
}

TEST(Subdivision, TorusTriangleCountsPerLevel) {
    const PolyMesh torus = readPolyMesh(kData + "catmark_torus_creases0.obj");
    EXPECT_EQ(torus.faceCount(), 32);
    EXPECT_EQ(torus.positions.size(), 32u);
    EXPECT_FALSE(torus.creases.empty());
    for (int level = 0; level <= 3; ++level)
        EXPECT_EQ(subdivide(torus, level, "torus").triangleCount(), std::size_t(2 * 32) << (2 * level)) << "level " << level;
}

TEST(Subdivision, CreasedEdgesKeepTheirMidpoints) {
    // A crease (sharpness >= 1) splits with the sharp rule at level 1: the new
    // edge vertex is the midpoint of the cage edge. Without the crease the
    // smooth rule pulls it towards the face centres.
    PolyMesh torus = readPolyMesh(kData + "catmark_torus_creases0.obj");
    const TriangleMesh creased = subdivide(torus, 1, "torus");
    PolyMesh smooth = torus;
    smooth.creases.clear();
    const TriangleMesh rounded = subdivide(smooth, 1, "torus");
    float worstCreased = 0, bestSmooth = 1e30f;
    for (const Crease& c : torus.creases) {
        ASSERT_GE(c.sharpness, 1.0f);
        const Vec3f mid = (torus.positions[std::size_t(c.v0)] + torus.positions[std::size_t(c.v1)]) * 0.5f;
        worstCreased = std::max(worstCreased, distanceToNearestVertex(creased, mid));
        bestSmooth = std::min(bestSmooth, distanceToNearestVertex(rounded, mid));
    }
    EXPECT_LT(worstCreased, 1e-5f);
    EXPECT_GT(bestSmooth, 1e-2f);
}

TEST(MeshLoading, BadFilesGiveOneLineErrors) {
    test::TempDir dir;
    test::writeText(dir / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    test::writeText(dir / "empty.obj", "v 0 0 0\n");
    test::writeText(dir / "nomtl.obj", "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    test::writeText(dir / "trunc.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0\n");
    test::writeText(dir / "shape.stl", "solid x\n");
    const struct {
        std::string file, expected;
    } cases[] = {{"range.obj", "vertex"},      {"empty.obj", "has no faces"}, {"nomtl.obj", "missing.mtl"},
                 {"trunc.ply", "trunc.ply"},   {"shape.stl", "unknown mesh format '.stl'"},
                 {"absent.obj", "no such file"}};
    for (const auto& c : cases) {
        const std::string msg = errorOf([&] { readPolyMesh((dir / c.file).string()); });
        EXPECT_NE(msg.find(c.expected), std::string::npos) << c.file << ": " << msg;
        EXPECT_EQ(msg.find("Use default material"), std::string::npos) << msg;  // the loader's words, not weft's
        EXPECT_EQ(msg.find('\n'), std::string::npos) << c.file << ": " << msg;
        EXPECT_NE(msg.find(c.file), std::string::npos) << msg;
    }
}

TEST(MeshScene, JsonMeshEntriesAreCheckedWithPositions) {
    test::TempDir dir;
    std::filesystem::copy(kData + "catmark_torus_creases0.obj", dir / "torus.obj");
    test::writeText(dir / "ok.json", R"({"meshes": [{"file": "torus.obj", "subdivision": 2, "scale": 2, "translate": [0, 1, 0]}]})");
    const Scene scene = loadScene((dir / "ok.json").string());
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].triangleCount(), 64u * 16u);
    EXPECT_GT(scene.worldBox().extents().x(), 4.0);  // scaled by 2

    test::writeText(dir / "bad.json", "{\"meshes\": [{\"file\": \"torus.obj\",\n \"subdivide\": 2}]}");
    std::string msg = errorOf([&] { loadScene((dir / "bad.json").string()); });
    EXPECT_NE(msg.find("bad.json:2:2: unknown key 'subdivide' in mesh; valid keys: file, rotate, scale, subdivision, translate"), std::string::npos) << msg;
    test::writeText(dir / "level.json", R"({"meshes": [{"file": "torus.obj", "subdivision": 9}]})");
    msg = errorOf([&] { loadScene((dir / "level.json").string()); });
    EXPECT_NE(msg.find("level.json:1:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("outside [0, 8]"), std::string::npos) << msg;
    test::writeText(dir / "missing.json", R"({"meshes": [{"file": "nope.obj"}]})");
    msg = errorOf([&] { loadScene((dir / "missing.json").string()); });
    EXPECT_NE(msg.find("missing.json:1:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
}

TEST(MeshScene, BareMeshIsFramedAndLit) {
    const Scene scene = loadScene(kData + "catmark_torus_creases0.obj", 1.0);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.render.technique.value_or(""), "mesh.pathtrace");
    EXPECT_EQ(scene.lights.size(), 1u);  // no emissive material: a key light
    const BBoxd box = scene.worldBox();
    EXPECT_NEAR((scene.camera.target - box.getCenter()).length(), 0.0, 1e-9);
    EXPECT_GT(scene.camera.eye.z(), box.max().z());
}

// tinyobjloader reads a word it cannot parse as 0; weft names it instead.
TEST(MeshLoading, ObjCoordinatesThatAreNotFiniteNumbersAreErrors) {
    test::TempDir dir;
    for (const std::string word : {"inf", "-inf", "nan", "1,5", "1e400", "x"}) {
        test::writeText(dir / "bad.obj", "v 0 0 0\nv 1 0 0\n  v 0 " + word + " 0\nf 1 2 3\n");
        const std::string msg = errorOf([&] { readPolyMesh((dir / "bad.obj").string()); });
        EXPECT_NE(msg.find("bad.obj': line 3: vertex coordinate '" + word + "' is not a finite number"), std::string::npos) << msg;
    }
    // Comments, CRLF line ends and vertex colours are still read.
    test::writeText(dir / "ok.obj", "v 0 0 0 # origin\r\nv 1 0 0 1 0.5 0\r\nv 0 1 0\r\nvn 0 0 1\r\nf 1 2 3\r\n");
    const PolyMesh poly = readPolyMesh((dir / "ok.obj").string());
    ASSERT_EQ(poly.positions.size(), 3u);
    EXPECT_EQ(poly.positions[1], Vec3f(1, 0, 0));
}
