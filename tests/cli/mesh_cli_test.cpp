// The weft host with meshes: a bare .obj renders with the path tracer, the
// VPL technique writes its AOVs and pass timings, and a bad mesh is a
// one-line error that leaves no file behind.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/image/io/image_io.hpp"
#include "tests/support/test_support.hpp"

using namespace weft::test;

namespace {
const std::string kData = std::string(WEFT_SOURCE_DIR) + "/data/";
}

TEST(MeshCli, BareObjRendersWithThePathTracer) {
    TempDir dir;
    const auto r = runWeft("render " + kData + "catmark_torus_creases0.obj --res 32x24 --spp 4 -o " + (dir / "t.exr").string());
    ASSERT_EQ(r.status, 0) << r.output;
    weft::Metadata md;
    const weft::Image img = weft::readImage((dir / "t.exr").string(), &md);
    bool technique = false;
    for (const auto& [k, v] : md) technique |= k == "weft:technique" && v == "mesh.pathtrace";
    EXPECT_TRUE(technique);
    double lit = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) lit += img.at(x, y, 0) > 0 ? 1 : 0;
    EXPECT_GT(lit, 0.1 * 32 * 24);  // the torus is in the frame and lit
}

TEST(MeshCli, VplDeferredWritesAovsAndPassTimings) {
    TempDir dir;
    const auto r = runWeft("render " + std::string(WEFT_SOURCE_DIR) + "/scenes/cornell.json --res 32x32 --set interleave=2x2 -o " +
                           (dir / "c.exr").string() + " --stats " + (dir / "c.json").string());
    ASSERT_EQ(r.status, 0) << r.output;
    const weft::Image img = weft::readImage((dir / "c.exr").string());
    for (const char* ch : {"direct.R", "indirect.B", "albedo.G", "N.Z", "Z", "discontinuity", "subbuffer"})
        EXPECT_GE(img.channelIndex(ch), 0) << ch;
    const auto stats = nlohmann::json::parse(readBytes(dir / "c.json"));
    for (const char* pass : {"VG.vpls", "BC.gbuffer", "SSM.shade", "KK.bias_compensation", "DB.discontinuity", "B.blur", "C.compose"})
        EXPECT_TRUE(stats["timings_ms"].contains(pass)) << pass;
    for (const char* fused : {"BS.split", "BG.gather"}) EXPECT_FALSE(stats["timings_ms"].contains(fused)) << fused;
    EXPECT_GT(stats["counters"]["rays.shadow"].get<long long>(), 0);
    // The paper's split and gather copies, when asked for, are timed as passes of their own.
    const auto copies = runWeft("render " + std::string(WEFT_SOURCE_DIR) + "/scenes/cornell.json --res 32x32 --set interleave=2x2 --set split=one_pass -o " +
                                (dir / "s.exr").string() + " --stats " + (dir / "s.json").string());
    ASSERT_EQ(copies.status, 0) << copies.output;
    const auto split = nlohmann::json::parse(readBytes(dir / "s.json"));
    for (const char* pass : {"BS.split", "SSM.shade", "BG.gather"}) EXPECT_TRUE(split["timings_ms"].contains(pass)) << pass;
}

TEST(MeshCli, BadMeshIsAOneLineErrorAndNoFile) {
    TempDir dir;
    writeText(dir / "bad.obj", "v 0 0 0\nf 1 2 3\n");
    const auto r = runWeft("render " + (dir / "bad.obj").string() + " -o " + (dir / "o.exr").string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("bad.obj': a face refers to vertex"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "o.exr"));
}
