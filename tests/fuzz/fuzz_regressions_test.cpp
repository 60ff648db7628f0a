// The fuzz targets (tests/fuzz/*_target.hpp) in the default suite: each
// target accepts a well-formed input and refuses a broken one with a
// weft::Error, the scene dictionary names every key the loader accepts, and
// every crash or hang the fuzzers found is fed through the same function
// here, asserting a clean refusal or a correct result.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "core/base/files/json_doc.hpp"
#include "core/image/io/image_io.hpp"
#include "tests/fuzz/exr_target.hpp"
#include "tests/fuzz/mesh_target.hpp"
#include "tests/fuzz/raw_target.hpp"
#include "tests/fuzz/scene_json_target.hpp"
#include "tests/fuzz/text_parsers_target.hpp"
#include "tests/fuzz/vdb_target.hpp"
#include "tests/fuzz/volume_file_target.hpp"
#include "tests/support/vdb_fixtures.hpp"
#include "tests/support/volume_files.hpp"

namespace weft::fuzz {
namespace {

using Target = Outcome (*)(const std::uint8_t*, std::size_t);

Outcome feed(Target target, const std::string& bytes) {
    return target(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// A refusal is one non-empty line.
void expectRefused(const Outcome& o) {
    EXPECT_FALSE(o.accepted);
    EXPECT_FALSE(o.skipped);
    EXPECT_FALSE(o.message.empty());
    EXPECT_EQ(o.message.find('\n'), std::string::npos) << o.message;
}

void expectAccepted(const Outcome& o) {
    EXPECT_TRUE(o.accepted) << o.message;
    EXPECT_FALSE(o.skipped);
}

// ---- each target accepts what is well formed, refuses what is not ----------

TEST(FuzzTargets, SceneJson) {
    expectAccepted(feed(sceneJson, R"({"volumes": [{"procedural": "sphere", "resolution": 8}],
        "render": {"technique": "volume.raymarch", "res": [16, 16], "set": {"step": 0.5}}})"));
    expectAccepted(feed(sceneJson, R"({"volumes": [{"file": "fuzz.vdb"}], "meshes": [{"file": "fuzz.obj", "subdivision": 1}],
        "render": {"technique": "mesh.pathtrace"}})"));
    expectRefused(feed(sceneJson, R"({"volumes": [{"file": "fuzz.vdb"}], "render": {"technique": "volume.raymarch", "set": {"nope": 1}}})"));
    expectRefused(feed(sceneJson, "{\"camera\": "));
    EXPECT_TRUE(feed(sceneJson, R"({"volumes": [{"procedural": "cloud", "resolution": 1024}]})").skipped);
}

TEST(FuzzTargets, VdbFile) {
    const auto path = scratchDir() / "seed_sphere.vdb";
    test::writeProceduralVdb(path, "sphere", 8);
    const std::string bytes = slurp(path);
    expectAccepted(feed(vdbFile, bytes));
    expectRefused(feed(vdbFile, bytes.substr(0, bytes.size() / 2)));
    expectRefused(feed(vdbFile, "not a vdb"));
}

TEST(FuzzTargets, ObjAndPly) {
    expectAccepted(feed(objFile, "mtllib fuzz.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl m\nf 1 2 3 4\n"
                                 "#MTL\nnewmtl m\nKd 0.2 0.4 0.6\n"));
    expectRefused(feed(objFile, "v 0 0 0\nv 1 0 0\nf 1 2 9\n"));
    expectRefused(feed(objFile, "v 0 0 1e39\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));  // overflows to inf
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    expectAccepted(feed(plyFile, header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
    expectRefused(feed(plyFile, header.substr(0, 40)));
}

TEST(FuzzTargets, RawVolume) {
    const std::string header{char(0), char(0), char(0), char(3), char(3)};  // u8, little, plain, 4 x 4
    expectAccepted(feed(rawVolume, header + char(0) + std::string(64, '\7')));
    expectRefused(feed(rawVolume, header + char(0) + std::string(63, '\7')));                  // 63 bytes: not 4x4xZ
    expectRefused(feed(rawVolume, std::string{char(0), char(0), char(1), char(3), char(3), char(3)} + "not gzip"));
    expectRefused(feed(rawVolume, std::string{char(8), char(0), char(0), char(0), char(0), char(0), char(1)}));  // type "x"
}

TEST(FuzzTargets, VolumeFiles) {
    const openvdb::Coord dims(2, 2, 2);
    const std::string samples = "\1\2\3\4\5\6\7\10";
    const std::string nrrd = test::nrrdHeader(test::nrrdFields("uchar", dims));
    expectAccepted(feed(nrrdVolume, nrrd + samples));
    expectRefused(feed(nrrdVolume, nrrd + samples.substr(0, 7)));
    expectRefused(feed(nrrdVolume, test::nrrdHeader(test::nrrdFields("uchar", dims, "little", "bzip2")) + samples));
    // A claim too large to read per input is planned, then skipped.
    EXPECT_TRUE(feed(nrrdVolume, test::nrrdHeader(test::nrrdFields("float", {256, 256, 256}))).skipped);
    const std::string npy = test::npyFile(test::npyDict("|u1", false, "(2, 2, 2)"), samples);
    expectAccepted(feed(npyVolume, npy));
    expectRefused(feed(npyVolume, npy.substr(0, npy.size() - 1)));
    expectRefused(feed(npyVolume, test::npyFile(test::npyDict("<c8", false, "(2, 2, 2)"), samples)));
    const std::string vtk = test::vtkHeader("BINARY", dims, "unsigned_char");
    expectAccepted(feed(vtkVolume, vtk + samples));
    expectAccepted(feed(vtkVolume, test::vtkHeader("ASCII", dims, "float") + "1 2 3 4\n5 6 7 8\n"));
    expectRefused(feed(vtkVolume, test::vtkHeader("ASCII", dims, "float") + "1 2 3 nan 5 6 7 8\n"));
    expectRefused(feed(vtkVolume, vtk.substr(0, vtk.size() / 2)));
}

TEST(FuzzTargets, ExrFile) {
    Image img(4, 4, {"R", "G", "B", "A"});
    const auto path = scratchDir() / "seed_tile.exr";
    writeExr(img, path.string(), {{"weft:tile", "1/1"}, {"weft:tile:full_resolution", "4x4"}, {"weft:complete", "1"}},
             ImageWindow{0, 0, 4, 4});
    const std::string bytes = slurp(path);
    expectAccepted(feed(exrFile, bytes));
    expectRefused(feed(exrFile, bytes.substr(0, bytes.size() - 20)));
    expectRefused(feed(exrFile, "not an exr"));
    // A legitimate image too large to read per input is checked, then skipped.
    Image large(1024, 512, {"R", "G", "B", "A"});
    const auto largePath = scratchDir() / "large.exr";
    writeExr(large, largePath.string(), {});
    EXPECT_TRUE(feed(exrFile, slurp(largePath)).skipped);
    const std::string largeBytes = slurp(largePath);
    expectRefused(feed(exrFile, largeBytes.substr(0, 200)));
}

TEST(FuzzTargets, TextParsers) {
    const auto text = [](int parser, const std::string& s) { return feed(textParsers, std::string(1, char(parser)) + s); };
    expectAccepted(text(0, "1001-1100x2"));
    expectRefused(text(0, "3,3"));
    expectAccepted(text(1, std::string(1, '\1') + "f.#.exr"));  // frame 7 -> f.0007.exr, checked by the target
    expectAccepted(text(2, "3/4"));
    expectRefused(text(2, "5/4"));
    expectAccepted(text(3, "640x480"));
    expectRefused(text(3, "0x480"));
    expectAccepted(text(4, "resolution 32x32\nframes 1-3\noutput o.#.exr\ntile 1/2"));
    expectRefused(text(4, "frames 1-3\noutput o.exr"));  // three frames into one file
    expectRefused(text(5, std::string(1, '\0') + "no_such_parameter=1"));
    expectAccepted(text(6, "4,4,4\n1,1,2"));
    expectRefused(text(6, "4,4\n1,1,2"));
}

// ---- the scene dictionary ----------------------------------------------------

std::set<std::string> dictionaryKeys() {
    std::ifstream in(std::string(WEFT_SOURCE_DIR) + "/tests/fuzz/scene.dict");
    std::set<std::string> keys;
    const std::regex entry(R"re(^key_\w+="\\"([^\\]+)\\":"$)re");
    std::smatch m;
    for (std::string line; std::getline(in, line);)
        if (std::regex_match(line, m, entry)) keys.insert(m[1]);
    return keys;
}

// The keys an object of the scene accepts, from the loader's own message
// for an unknown key ("...; valid keys: a, b, c").
std::vector<std::string> keysListedFor(const std::string& scene) {
    const Outcome o = feed(sceneJson, scene);
    EXPECT_FALSE(o.accepted) << scene;
    const std::size_t at = o.message.find("valid keys: ");
    EXPECT_NE(at, std::string::npos) << o.message;
    std::vector<std::string> keys;
    std::stringstream list(o.message.substr(at + 12));
    for (std::string k; std::getline(list, k, ',');) keys.push_back(k.substr(k.find_first_not_of(' ')));
    return keys;
}

TEST(FuzzRegressions, SceneDictionaryHasEveryKey) {
    const std::set<std::string> dict = dictionaryKeys();
    const std::string sphere = R"("procedural": "sphere", "resolution": 4)";
    for (const std::string& scene :
         {std::string(R"({"zzz": 1})"), std::string(R"({"volumes": [{"zzz": 1}]})"), std::string(R"({"meshes": [{"zzz": 1}]})"),
          std::string(R"({"lights": [{"zzz": 1}]})"), std::string(R"({"camera": {"zzz": 1}})"),
          std::string(R"({"camera": {"keys": [{"zzz": 1}]}})"), R"({"volumes": [{)" + sphere + R"(, "medium": {"zzz": 1}}]})",
          R"({"volumes": [{)" + sphere + R"(, "transfer_function": {"zzz": 1}}]})",
          R"({"volumes": [{)" + sphere + R"(, "transfer_function": {"points": [{"zzz": 1}]}}]})",
          R"({"volumes": [{)" + sphere + R"(, "grids": {"zzz": 1}}]})", R"({"volumes": [{)" + sphere + R"(, "emission": {"zzz": 1}}]})",
          R"({"volumes": [{)" + sphere + R"(, "motion": {"zzz": 1}}]})",
          std::string(R"({"render": {"zzz": 1}})")}) {
        const std::vector<std::string> keys = keysListedFor(scene);
        EXPECT_FALSE(keys.empty()) << scene;
        for (const std::string& k : keys) EXPECT_TRUE(dict.count(k)) << "tests/fuzz/scene.dict lacks \"" << k << "\" (" << scene << ")";
    }
    for (const RenderOption& o : renderOptions()) {
        if (!(o.places & kInScene)) continue;
        EXPECT_TRUE(dict.count(o.spec.name)) << o.spec.name;
        for (const std::string& alias : o.aliases) EXPECT_TRUE(dict.count(alias)) << alias;
    }
}

// ---- findings of the fuzz campaigns ------------------------------------------

// tests/fuzz/regressions/<target>/: inputs the fuzzers found that crashed or
// hung. Each must now be refused with one line, or accepted.
std::string regressionFile(const std::string& target, const std::string& name) {
    return slurp(std::filesystem::path(WEFT_SOURCE_DIR) / "tests/fuzz/regressions" / target / name);
}

// The stored finding `file` of `target` is refused in one line holding `text`.
void expectFindingRefused(Target target, const std::string& dir, const std::string& file, const std::string& text) {
    SCOPED_TRACE(dir + "/" + file);
    const Outcome o = feed(target, regressionFile(dir, file));
    expectRefused(o);
    EXPECT_NE(o.message.find(text), std::string::npos) << o.message;
}

TEST(FuzzRegressions, EveryStoredFindingIsHandled) {
    const std::map<std::string, Target> targets{{"scene_json", sceneJson}, {"vdb", vdbFile}, {"obj", objFile}, {"ply", plyFile},
                                                {"raw", rawVolume},        {"nrrd", nrrdVolume}, {"npy", npyVolume}, {"vtk", vtkVolume},
                                                {"exr", exrFile},          {"text", textParsers}};
    int cases = 0;
    for (const auto& [name, target] : targets) {
        const auto dir = std::filesystem::path(WEFT_SOURCE_DIR) / "tests/fuzz/regressions" / name;
        if (!std::filesystem::is_directory(dir)) continue;
        for (const auto& e : std::filesystem::directory_iterator(dir)) {
            SCOPED_TRACE(e.path().string());
            const Outcome o = feed(target, slurp(e.path()));
            if (!o.accepted && !o.skipped) expectRefused(o);
            ++cases;
        }
    }
    EXPECT_GE(cases, 1);
}

// A binary PLY whose face indices lie far beyond its 4 vertices crashed
// inside Assimp's vertex joining, which ran before weft checked them.
TEST(FuzzRegressions, PlyFaceIndexOutOfRangeIsRefused) {
    expectFindingRefused(plyFile, "ply", "face-index-out-of-range-be.ply", "mesh.ply");
}

Outcome frameNameInput(char frameIndex, const std::string& name) {
    return feed(textParsers, std::string{char(1), frameIndex} + name);
}

// Sixteen '#' are 64 digits; the name was cut to 63 in a fixed buffer.
TEST(FuzzRegressions, SixteenHashesExpandToSixtyFourDigits) {
    expectAccepted(frameNameInput(1, "f." + std::string(16, '#') + ".exr"));  // checked by the target
    expectAccepted(frameNameInput(4, std::string(40, '#')));
    EXPECT_EQ(expandFrameName(std::string(16, '#'), -5), "-" + std::string(62, '0') + "5");  // the sign counts in the width
}

// "%<digits>d" with more digits than an int holds overflowed while reading
// the width (UBSan: signed integer overflow); such a width is no wildcard.
TEST(FuzzRegressions, HugePrintfWidthIsNoWildcard) {
    expectAccepted(frameNameInput(0, "f.%99999999999999999999d.exr"));
    EXPECT_FALSE(hasFrameWildcard("f.%99999999999999999999d.exr"));
    EXPECT_EQ(expandFrameName("f.%99999999999999999999d.#.exr", 5), "f.%99999999999999999999d.0005.exr");
    EXPECT_EQ(expandFrameName("f.%032d.exr", 5), "f." + std::string(31, '0') + "5.exr");
}

// "property list uchar ply" (no value type, no name) and an "end_header"
// with text after it crashed inside Assimp's PLY parser.
TEST(FuzzRegressions, MalformedPlyPropertyIsRefusedBeforeAssimp) {
    expectFindingRefused(plyFile, "ply", "list-property-without-name.ply", "PLY header line 9 is malformed");
}

// "element face" declared twice, and vertices with x but no y or z: Assimp's
// PLY reader wrote past its buffers (ASan's allocator found its own chunk
// headers overwritten).
TEST(FuzzRegressions, PlyElementDeclaredTwiceIsRefusedBeforeAssimp) {
    expectFindingRefused(plyFile, "ply", "face-declared-twice-vertex-without-y.ply", "declares element 'face' twice");
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n";
    const Outcome noZ = feed(plyFile, header + "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                               "0 0\n1 0\n0 1\n3 0 1 2\n");
    EXPECT_NE(noZ.message.find("declares no vertex property z"), std::string::npos) << noZ.message;
}

// An element named "888888888888888888888888+88888888888fHce" kept
// Assimp's PLY reader busy for 20 s (and 400 MB): names must be words.
TEST(FuzzRegressions, PlyElementNameThatIsNoWordIsRefusedBeforeAssimp) {
    expectFindingRefused(plyFile, "ply", "element-name-of-digits-and-plus-hangs-assimp.ply", "PLY header line 8 is malformed");
}

// A corrupt leaf buffer claimed 0x6e6f697373657270 compressed bytes (the
// text "pression" read as a size): OpenVDB's blosc reader allocated it. A
// normal build's operator new throws std::bad_alloc, which the loader turns
// into one line; sanitized builds get the same (cmake/sanitize_bounded_new.cpp).
TEST(FuzzRegressions, VdbBloscSizeOfEightExabytesIsRefused) {
    expectFindingRefused(vdbFile, "vdb", "blosc-claims-8-exabytes.vdb", "blosc chunk of 7957695011165139568 bytes runs past the end");
}

// A 16^3 node's values stated an uncompressed blosc chunk of
// 648518346341351408 bytes where its mask left none: OpenVDB 10's
// bloscFromStream copies the stated bytes before comparing, and wrote the
// rest of the file (4317 bytes) into an empty buffer (ASan:
// heap-buffer-overflow). The preflight now walks every chunk of a float tree.
TEST(FuzzRegressions, VdbUncompressedBloscChunkLongerThanItsNodeIsRefused) {
    expectFindingRefused(vdbFile, "vdb", "uncompressed-blosc-chunk-overflows-its-buffer.vdb",
                         "uncompressed blosc chunk of ");
}

// A root tile whose active flag was the byte 2: OpenVDB reads it into a
// bool (UBSan: load of value 2, which is not a valid value for type 'bool').
TEST(FuzzRegressions, VdbRootTileFlagThatIsNoBoolIsRefused) {
    expectFindingRefused(vdbFile, "vdb", "root-tile-flag-2-is-no-bool.vdb", "root tile flag 2 (not 0 or 1)");
}

// A root tile at x = INT_MIN: its active box was framed one voxel wider,
// INT_MIN - 1 (UBSan: signed integer overflow in Coord::offset). Root
// origins beyond +-2^30 are refused, so no coordinate sum overflows.
TEST(FuzzRegressions, VdbRootTileAtTheIntLimitIsRefused) {
    expectFindingRefused(vdbFile, "vdb", "root-tile-origin-at-int-min.vdb",
                         "root tile origin -2147483648 lies beyond the index range +-2^30");
}

// A 40 KB file of format version 0: OpenVDB's reader of the pre-release
// layouts, which the preflight did not walk, peaked at 1.7 GB before it
// gave up. Such versions are now refused before OpenVDB opens the file.
TEST(FuzzRegressions, VdbOfFormatVersionZeroIsRefusedBeforeOpenVdb) {
    expectFindingRefused(vdbFile, "vdb", "format-version-0-peaks-at-1.7GB.vdb", "file format version 0 is not one weft reads");
}

// A channel list of 73 bytes whose last byte was the first of a fifth
// channel's name, not the list's terminator: the walk took it for one, and
// OpenEXR, reading the names on, took an attribute size of 825 MB from the
// bytes after the header and allocated it.
TEST(FuzzRegressions, ExrChannelListCutInsideANameIsRefusedBeforeOpenExr) {
    expectFindingRefused(exrFile, "exr", "chlist-last-name-cut-by-its-size.exr",
                         "the channel list does not end where its attribute's 73 bytes end");
}

// A channel list that stated 73 bytes but whose list, read as OpenEXR reads
// it, ended elsewhere: the preflight's walk and OpenEXR's saw different
// headers, and OpenEXR's held a data window 2359300 pixels wide, which it
// allocated (370 ms under ASan) before finding the data missing.
TEST(FuzzRegressions, ExrChannelListOfAnotherSizeIsRefusedBeforeOpenExr) {
    expectFindingRefused(exrFile, "exr", "chlist-size-hides-a-wide-data-window.exr",
                         "the channel list does not end where its attribute's 73 bytes end");
}

// A complete tile whose weft:counter: attribute was no number: the merge's
// std::stoll threw std::invalid_argument out of weft merge.
TEST(FuzzRegressions, ExrTileCounterThatIsNoNumberIsRefused) {
    const std::string path = writeScratch("tile.exr", regressionFile("exr", "tile-counter-that-is-no-number.exr"));
    const Outcome merged = guarded([&] { mergeTiles({path}); });
    expectRefused(merged);
    EXPECT_NE(merged.message.find("is not a count (corrupt tile)"), std::string::npos) << merged.message;
    EXPECT_TRUE(feed(exrFile, regressionFile("exr", "tile-counter-that-is-no-number.exr")).accepted);  // as an image it reads
}

}  // namespace
}  // namespace weft::fuzz
