// Bad input: one clear line on stderr naming the problem, non-zero exit, no
// output file created, and an existing file at the output path untouched.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>

#include "tests/support/test_support.hpp"
#include "tests/support/vdb_fixtures.hpp"

using namespace weft::test;

namespace {

struct BadInputCase {
    const char* name;
    std::string args;      // everything after "render", before -o
    const char* expected;  // a fragment the error line must contain
};

void PrintTo(const BadInputCase& c, std::ostream* os) { *os << c.name; }

class RenderErrors : public ::testing::TestWithParam<BadInputCase> {
protected:
    void SetUp() override {
        writeProceduralVdb(dir / "sphere.vdb", "sphere", 16);
        writeText(dir / "notvdb.vdb", "this is not a vdb file\n");
        writeText(dir / "bad.json", "{\n  \"volumes\": [ { \"procedural\": \"sphere\", \"resolution\": 16 } ],\n  \"camra\": {}\n}\n");
        writeText(dir / "syntax.json", "{\n  \"volumes\": [\n    { \"procedural\": \"sphere\" },\n  ]\n}\n");
        writeText(dir / "cut.ply", "ply\nformat ascii 1.0\nelement vertex 3\nprop");
        std::filesystem::create_directory(dir / "folder.obj");
        mkfifo((dir / "pipe.vdb").c_str(), 0600);
        writeProceduralVdb(dir / "whole.vdb", "cloud", 32);
        {  // a VDB cut in the middle of its grid data
            const std::string bytes = readBytes(dir / "whole.vdb");
            writeText(dir / "cut.vdb", bytes.substr(0, bytes.size() / 2));
        }
        writeText(dir / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
        writeText(dir / "mixed.json", "{\"volumes\": [{\"procedural\": \"sphere\", \"resolution\": 8}],\n"
                                      " \"meshes\": [{\"file\": \"tri.obj\"}, {\"file\": \"tri.obj\", \"translate\": [0, 0, -1]}]}\n");
        std::filesystem::create_symlink(dir / "loop2.vdb", dir / "loop1.vdb");
        std::filesystem::create_symlink(dir / "loop1.vdb", dir / "loop2.vdb");
        std::filesystem::create_symlink(dir / "gone.obj", dir / "dangling.obj");
        writeText(dir / "huge.json", "{\"camera\": {\"fov\": 1" + std::string(400, '0') + "}}\n");
        // Coordinates Embree would abort on (ray origins past 1.8e18), or float precision long lost.
        writeText(dir / "far.obj", "v -1 -1 0\nv 1.188e23 -1 0\nv 0 1 0\nf 1 2 3\n");
        writeText(dir / "far.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                   "-1 -1 0\n1.188e23 -1 0\n0 1 0\n3 0 1 2\n");
        writeText(dir / "far_eye.json", "{\"meshes\": [{\"file\": \"tri.obj\"}], \"camera\": {\"eye\": [0, 0, 1e19], \"target\": [0, 0, 0]}}\n");
        writeText(dir / "far_light.json", "{\"meshes\": [{\"file\": \"tri.obj\"}], \"lights\": [{\"type\": \"point\", \"position\": [0, 2e12, 0]}]}\n");
        writeText(dir / "far_volume.json", "{\"volumes\": [{\"procedural\": \"sphere\", \"resolution\": 8, \"translate\": [0, 0, 999999999999], \"scale\": 1e8}]}\n");
        writeText(dir / "tiny_voxels.json", "{\"volumes\": [{\"file\": \"sphere.vdb\", \"scale\": 1e-12}]}\n");
        writeText(dir / "huge_voxels.json", "{\"volumes\": [{\"procedural\": \"sphere\", \"resolution\": 8, \"scale\": 1e9}]}\n");
        writeText(dir / "inf.mtl", "newmtl shiny\nKd 0.5 0.5 0.5\nKs 0.5 0.5 0.5\nNs 1e39\n");
        writeText(dir / "shiny.obj", "mtllib inf.mtl\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nusemtl shiny\nf 1 2 3\n");
        mkfifo((dir / "pipe.mtl").c_str(), 0600);
        writeText(dir / "piped.obj", "mtllib pipe.mtl\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
        writeText(dir / "late_camera.json", "{\"volumes\": [{\"file\": \"missing.vdb\"}],\n"
                                            " \"camera\": {\"eye\": [0, 0, 1], \"target\": [0, 0, 0], \"up\": [0, 0, 1]}}\n");
        writeText(dir / "late_key.json", "{\"volumes\": [{\"file\": \"missing.vdb\"}, {\"procedural\": \"sphere\", \"scael\": 2}]}\n");
        writeText(dir / "deep.json", std::string(100000, '[') + std::string(100000, ']'));
        {
            std::string many = "{\"volumes\": [";
            for (int i = 0; i < 1000; ++i) many += std::string(i ? ", " : "") + "{\"procedural\": \"cloud\", \"resolution\": 128}";
            writeText(dir / "many_volumes.json", many + "]}\n");
        }
        writeText(dir / "far_translate.json", "{\"volumes\": [{\"procedural\": \"sphere\", \"resolution\": 8, \"translate\": [1e300, 0, 0]}]}\n");
        writeText(dir / "literal.json", "{\"camera\": {\"x\": tru}}\n");
        writeText(dir / "range.json", "{\n  \"volumes\": [ { \"procedural\": \"sphere\", \"resolution\": 2 } ]\n}\n");
    }
    // $D: the test's folder; $O: the output path the test passes with -o.
    std::string substitute(std::string args, const std::filesystem::path& out) const {
        for (std::size_t at; (at = args.find("$D")) != std::string::npos;) args.replace(at, 2, dir.path().string());
        for (std::size_t at; (at = args.find("$O")) != std::string::npos;) args.replace(at, 2, out.string());
        return args;
    }
    TempDir dir;
};

TEST_P(RenderErrors, OneLineNonZeroExitNoOutput) {
    const BadInputCase& c = GetParam();
    const auto out = dir / "out.exr";
    const CommandResult r = runWeft("render " + substitute(c.args, out) + " -o " + out.string());
    EXPECT_NE(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_EQ(r.output.rfind("weft: error: ", 0), 0u) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST_P(RenderErrors, ExistingOutputIsLeftUntouched) {
    const BadInputCase& c = GetParam();
    const auto out = dir / "keep.exr";
    writeText(out, "precious user file");
    const CommandResult r = runWeft("render " + substitute(c.args, out) + " -o " + out.string());
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(readBytes(out), "precious user file");
    for (const auto& e : std::filesystem::directory_iterator(dir.path()))
        EXPECT_EQ(e.path().filename().string().find(".weft-tmp-"), std::string::npos) << e.path();
}

INSTANTIATE_TEST_SUITE_P(
    BadInput, RenderErrors,
    ::testing::Values(
        BadInputCase{"MissingFile", "$D/nope.vdb", "no such file"},
        BadInputCase{"NotAVdb", "$D/notvdb.vdb", "not an OpenVDB file"},
        BadInputCase{"NoSuchGrid", "$D/sphere.vdb --grid temperature", "no grid named 'temperature' (grids: density)"},
        BadInputCase{"UnknownTechnique", "builtin:sphere --technique volume.nope", "unknown technique 'volume.nope' (known:"},
        BadInputCase{"UnknownKey", "builtin:sphere --set stpe=1", "unknown parameter 'stpe'; valid parameters: step"},
        BadInputCase{"OutOfRange", "builtin:sphere --set step=-1", "bad value '-1' for parameter 'step' (float, allowed [1e-04, 64])"},
        BadInputCase{"NotANumber", "builtin:sphere --set step=abc", "not a number"},
        BadInputCase{"MissingEquals", "builtin:sphere --set step", "expected key=value"},
        BadInputCase{"BadResolution", "builtin:sphere --res 0x10", "--res '0x10': expected WxH"},
        BadInputCase{"BadResolutionText", "builtin:sphere --res big", "--res 'big': expected WxH"},
        BadInputCase{"UnknownBuiltin", "builtin:teapot", "unknown built-in scene 'builtin:teapot'"},
        BadInputCase{"UnknownInputKind", "$D/scene.txt", "expected a scene .json, a .vdb, .obj or .ply file"},
        BadInputCase{"UnknownSceneKey", "$D/bad.json", "bad.json:3:3: unknown key 'camra' in scene; valid keys: camera"},
        BadInputCase{"SceneSyntax", "$D/syntax.json", "syntax.json:4:3: JSON syntax error: in a value: unexpected ']'; expected '[', '{', or a literal"},
        BadInputCase{"SceneBadLiteral", "$D/literal.json", "literal.json:1:21: JSON syntax error: in a value: invalid literal at '"},
        BadInputCase{"SceneValueRange", "$D/range.json", "range.json:2:56: volume.resolution = 2 is outside [4, 1024]"},
        BadInputCase{"StatsOverwritesOutput", "builtin:sphere --res 8x8 --stats $O", "--stats names the same file as -o"},
        BadInputCase{"PreviewOverwritesStats", "builtin:sphere --res 8x8 --preview $D/p.png --stats $D/p.png", "--stats names the same file as --preview"},
        BadInputCase{"SceneDroppedByImageTechnique", "$D/mixed.json --technique analytic.2d",
                     "analytic.2d renders no scene content, and the scene '"},
        BadInputCase{"EmptyFrames", "builtin:sphere --res 8x8 --frames ''", "--frames '' is empty"},
        BadInputCase{"HugeThreadCount", "builtin:sphere --res 8x8 --threads 2147483647", "--threads 2147483647 is outside [0, 4096]"},
        BadInputCase{"BadSetFailsOnceForAllFrames", "builtin:sphere --technique volume.raymarch --res 8x8 --frames 1-1000000 --set stpe=1",
                     "unknown parameter 'stpe'"},
        BadInputCase{"PlyHeaderCutShort", "$D/cut.ply --res 8x8", "its PLY header has no end_header line"},
        BadInputCase{"FolderAsMesh", "$D/folder.obj --res 8x8", "is a directory, not a file"},
        BadInputCase{"SymlinkLoopAsVolume", "$D/loop1.vdb --res 8x8", "is a loop of symbolic links"},
        BadInputCase{"DanglingSymlinkAsMesh", "$D/dangling.obj --res 8x8", "is a symbolic link to '"},
        BadInputCase{"HugeNumberInScene", "$D/huge.json --res 8x8", "number too large for a double: '100000000000000000000000000000000000000000000000000000000000...' (401 characters)"},
        BadInputCase{"FifoAsVolume", "$D/pipe.vdb --res 8x8", "is a FIFO (named pipe)"},
        BadInputCase{"DeviceAsMesh", "/dev/zero --res 8x8 --technique mesh.pathtrace", "expected a scene .json"},
        BadInputCase{"VdbCutShort", "$D/cut.vdb --res 8x8", "the file is cut short (grid 1 ends at byte "},
        BadInputCase{"ImageAboveMemory", "builtin:sphere --res 65536x65536", "needs about 128 GiB (32 bytes per pixel for its image and buffers"},
        BadInputCase{"DeferredBuffersAboveMemory", "$D/tri.obj --technique lighting.vpl_deferred --res 16384x16384 --max-memory 40",
                     "a 16384x16384 render with lighting.vpl_deferred needs about 64 GiB (256 bytes per pixel"},
        BadInputCase{"ImageAboveMaxMemory", "builtin:sphere --res 1024x1024 --max-memory 0.01",
                     "above the 0.01 GiB limit (--max-memory GiB"},
        BadInputCase{"BadSpp", "builtin:sphere --spp 0", "--spp 0 is outside"},
        BadInputCase{"ObjVertexBeyondTheWorld", "$D/far.obj --res 8x8", "mesh 0 spans (-1, -1, 0) to (1.188e+23, 1, 0), beyond the +-1e+12 scene units"},
        BadInputCase{"PlyVertexBeyondTheWorld", "$D/far.ply --res 8x8 --technique mesh.pathtrace", "beyond the +-1e+12 scene units"},
        BadInputCase{"CameraBeyondTheWorld", "$D/far_eye.json --res 8x8", "the camera's eye lies at (0, 0, 1e+19), beyond the +-1e+12"},
        BadInputCase{"PointLightBeyondTheWorld", "$D/far_light.json --res 8x8", "light 0's position lies at (0, 2e+12, 0)"},
        BadInputCase{"VolumeBeyondTheWorld", "$D/far_volume.json --res 8x8", "volume 0 ('procedural:sphere') spans"},
        BadInputCase{"VoxelsTooLargeAsPlaced", "$D/huge_voxels.json --res 8x8", "as placed is outside [1e-08, 1e+08] scene units"},
        BadInputCase{"PlacementTooSmall", "$D/tiny_voxels.json --res 8x8", "the placement makes the volume's transform singular"},
        BadInputCase{"MtlExponentBeyondFloat", "$D/shiny.obj --res 8x8", "material 'shiny': Ns inf is outside [0, 1e+06]"},
        BadInputCase{"MtllibIsAFifo", "$D/piped.obj --res 8x8", "material file '"},
        BadInputCase{"FilterRadiusAHairWide", "builtin:sphere --res 8x8 --set filter_radius=1e-300", "filter_radius 1e-300 is narrower than 0.01 pixels"},
        BadInputCase{"SeedJustPastTheRange", "builtin:sphere --res 8x8 --seed 9007199254740993", "9007199254740993"},
        BadInputCase{"CameraCheckedBeforeAnyVolumeLoads", "$D/late_camera.json --res 8x8", "camera.up must not be parallel"},
        BadInputCase{"LaterVolumeKeysCheckedBeforeAnyLoads", "$D/late_key.json --res 8x8", "unknown key 'scael' in volume"},
        BadInputCase{"NestingBounded", "$D/deep.json --res 8x8", "deep.json:1:257: JSON nested deeper than 256 levels"},
        BadInputCase{"SceneAboveMaxMemoryBeforeLoading", "$D/many_volumes.json --res 8x8 --max-memory 1",
                     "needs about 7.81 GiB to load (estimated from its files before reading them), above the 1 GiB limit"},
        BadInputCase{"TranslateBeyondTheWorld", "$D/far_translate.json --res 8x8", "translate must lie within +-1e+12 scene units"},
        BadInputCase{"OutputFolderMissing", "builtin:sphere --res 8x8 --preview $D/nofolder/p.png", "folder '"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(RenderOutput, MustBeExr) {
    TempDir dir;
    const CommandResult r = runWeft("render builtin:sphere --res 8x8 -o " + (dir / "out.png").string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("must be an .exr file"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
}

}  // namespace
