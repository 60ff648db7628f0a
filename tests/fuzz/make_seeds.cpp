// weft_fuzz_seeds OUT SOURCE: writes the fuzz targets' seed corpora into
// OUT/<target>/: small files made the way the tests make theirs
// (tests/support), copies of the project's committed data (SOURCE/data,
// SOURCE/scenes), and inputs in each target's own framing (tests/fuzz/*_target.hpp).
#include <openvdb/io/File.h>

#include <boost/iostreams/filter/gzip.hpp>
#include <boost/iostreams/filtering_stream.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/base/error.hpp"
#include "core/image/io/image_io.hpp"
#include "core/volume/volume.hpp"
#include "plugins/technique.hpp"
#include "tests/support/vdb_fixtures.hpp"
#include "tests/support/volume_files.hpp"

namespace fs = std::filesystem;

namespace {

fs::path out;

void write(const std::string& target, const std::string& name, const std::string& bytes) {
    fs::create_directories(out / target);
    std::ofstream(out / target / name, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string gzipped(const std::string& bytes) {
    std::ostringstream packed;
    {
        boost::iostreams::filtering_ostream gz;
        gz.push(boost::iostreams::gzip_compressor());
        gz.push(packed);
        gz.write(bytes.data(), std::streamsize(bytes.size()));
    }
    return packed.str();
}

void sceneSeeds(const fs::path& source) {
    for (const auto& e : fs::recursive_directory_iterator(source / "scenes"))
        if (e.path().extension() == ".json") write("scene_json", e.path().filename().string(), slurp(e.path()));
    write("scene_json", "volume_file.json",
          R"({"volumes": [{"file": "fuzz.vdb", "translate": [0, 0.1, 0], "rotate": [0, 30, 0], "scale": [1, 2, 1],
               "transfer_function": {"range": [0, 1], "points": [{"s": 0, "color": [1, 1, 1], "extinction": 0},
                                                                {"s": 1, "color": [1, 0.5, 0.2], "extinction": 4}]},
               "medium": {"absorb": [0.1, 0.1, 0.1], "scatter": [1, 1, 1], "g": 0.3}}],
  "lights": [{"type": "directional", "direction": [0, -1, 0], "color": [1, 1, 1], "intensity": 2}],
  "render": {"technique": "volume.singlescatter", "res": [32, 24], "spp": 2, "seed": 3, "set": {"compat": "vdb_render"}}})");
    write("scene_json", "procedural.json",
          R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 40},
  "volumes": [{"procedural": "cloud", "resolution": 16, "seed": 2}, {"procedural": "ct", "resolution": 8}],
  "render": {"technique": "volume.raymarch", "resolution": "16x16", "params": {"step": 0.5}}})");
    write("scene_json", "meshes.json",
          R"({"meshes": [{"file": "fuzz.obj", "subdivision": 1, "scale": 2}, {"file": "fuzz.ply", "translate": [0, 1, 0]}],
  "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 5}, {"type": "environment", "color": [0.2, 0.3, 0.4]}],
  "render": {"technique": "mesh.pathtrace"}})");
    write("scene_json", "camera_keys.json",
          R"({"camera": {"up": [0, 1, 0], "fov": 35, "shutter": [-0.25, 0.25],
             "keys": [{"frame": 1, "eye": [0, 0, 3], "target": [0, 0, 0]}, {"frame": 10, "eye": [3, 0, 0]}]},
  "volumes": [{"procedural": "sphere", "resolution": 8}]})");
}

void vdbSeeds() {
    const fs::path dir = out / "vdb";
    fs::create_directories(dir);
    weft::test::writeProceduralVdb(dir / "sphere8.vdb", "sphere", 8);
    weft::test::writeProceduralVdb(dir / "cloud12.vdb", "cloud", 12);
    weft::test::writeProceduralVdb(dir / "named.vdb", "sphere", 6, "smoke");
    weft::test::writeSlabVdb(dir / "slab.vdb", 4, 2, 0.5);
    weft::test::writeEmptyVdb(dir / "empty.vdb");
    // Two grids, one not float: the loader picks "density" and names the rest.
    auto density = weft::makeProceduralGrid("sphere", 6, 1);
    density->setName("density");
    auto velocity = openvdb::Vec3SGrid::create(openvdb::Vec3s(0));
    velocity->setName("vel");
    velocity->tree().setValue(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1, 0, 0));
    auto half = weft::makeProceduralGrid("cloud", 8, 3);
    half->setName("half");
    half->setSaveFloatAsHalf(true);
    openvdb::io::File file((dir / "several.vdb").string());
    file.write({density, velocity, half});
    file.close();
    // data/smoke_small.vdb (266 KB) is left out: libFuzzer's input length
    // follows the largest seed, and inputs that size run about once a second.
}

void objSeeds(const fs::path& source) {
    for (const char* dir : {"data", "data/cornell", "data/shapes"})
        for (const auto& e : fs::directory_iterator(source / dir)) {
            if (e.path().extension() != ".obj") continue;
            std::string obj = slurp(e.path());
            const fs::path mtl = fs::path(e.path()).replace_extension(".mtl");
            if (fs::exists(mtl)) {
                // The target writes the text after "#MTL" as fuzz.mtl.
                const std::string name = "mtllib " + mtl.filename().string();
                if (const auto at = obj.find(name); at != std::string::npos) obj.replace(at, name.size(), "mtllib fuzz.mtl");
                obj += "\n#MTL\n" + slurp(mtl);
            }
            write("obj", e.path().filename().string(), obj);
        }
    write("obj", "quad_creases.obj",
          "mtllib fuzz.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nusemtl glow\n"
          "f 1/1/1 2/1/1 3/1/1 4/1/1\nt crease 2/1/0 1 2 4.5\nt corner 1/1/0 3 7\n"
          "#MTL\nnewmtl glow\nKd 0.5 0.5 0.5\nKs 0.1 0.1 0.1\nNs 20\nKe 1 1 1\n");
}

std::string plyHeader(const std::string& format, bool normals) {
    return "ply\nformat " + format + " 1.0\ncomment fuzz seed\nelement vertex 4\nproperty float x\nproperty float y\n"
           "property float z\n" + (normals ? "property float nx\nproperty float ny\nproperty float nz\n" : "") +
           "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
}

template <class T>
void appendWord(std::string& s, T v, bool big) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big) std::reverse(b, b + sizeof(T));
    s.append(b, sizeof(T));
}

void plySeeds() {
    write("ply", "quad_ascii.ply", plyHeader("ascii", true) +
                                       "0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n3 0 2 3\n");
    write("ply", "quad_polygon.ply", plyHeader("ascii", false) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n2 0 1\n");
    for (const bool big : {false, true}) {
        std::string body;
        const float xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (const auto& p : xy) appendWord(body, p[0], big), appendWord(body, p[1], big), appendWord(body, 0.0f, big);
        for (const int face : {0, 1}) {
            body += char(3);
            for (const int v : {0, 1 + face, 2 + face}) appendWord(body, std::int32_t(v), big);
        }
        write("ply", big ? "quad_be.ply" : "quad_le.ply",
              plyHeader(big ? "binary_big_endian" : "binary_little_endian", false) + body);
    }
}

// The raw target's framing: type, byte order, gzip, X, Y, Z, then the file.
void rawSeeds() {
    const auto header = [](int type, int big, int gzip, int x, int y, int z) {
        return std::string{char(type), char(big), char(gzip), char(x - 1), char(y - 1), char(z - 1)};
    };
    std::string u8, u16, f32;
    for (int i = 0; i < 4 * 4 * 4; ++i) {
        u8 += char(i % 5 ? i * 3 : 0);
        appendWord(u16, std::uint16_t(i % 3 ? i * 1031 : 0), false);
        appendWord(f32, i % 4 ? float(i) * 0.25f - 3.0f : 0.0f, true);
    }
    write("raw", "u8.bin", header(0, 0, 0, 4, 4, 4) + u8);
    write("raw", "u16.bin", header(1, 0, 0, 4, 4, 4) + u16);
    write("raw", "f32_big.bin", header(2, 1, 0, 4, 4, 4) + f32);
    write("raw", "u8_gzip.bin", header(0, 0, 1, 4, 4, 4) + gzipped(u8));
    write("raw", "u16_gzip.bin", header(1, 0, 1, 4, 4, 4) + gzipped(u16));
}

// Small self-describing volumes (tests/support/volume_files.hpp), 4x3x2
// samples, in each encoding and layout the importers read.
void volumeFileSeeds() {
    const openvdb::Coord dims(4, 3, 2);
    std::string u8, i16le, i16be, f32le, f64be, ascii;
    for (int i = 0; i < 24; ++i) {
        u8 += char(i % 3 ? i * 9 : 0);
        appendWord(i16le, std::int16_t(i * 1500 - 9000), false);
        appendWord(i16be, std::int16_t(i * 1500 - 9000), true);
        appendWord(f32le, float(i) * 0.25f - 2.0f, false);
        appendWord(f64be, double(i) * 1e-3, true);
        ascii += std::to_string(i % 5) + (i % 4 == 3 ? "\n" : " ");
    }
    using weft::test::nrrdFields;
    using weft::test::nrrdHeader;
    const std::string geometry = "space: left-posterior-superior\nspace directions: (0.5,0,0) (0,0.5,0.1) (0,0,2)\n"
                                 "space origin: (-10,2,3.5)\n";
    write("nrrd", "short_big.nrrd", nrrdHeader(nrrdFields("short", dims, "big") + geometry) + i16be);
    write("nrrd", "uchar.nrrd", nrrdHeader(nrrdFields("uchar", dims) + "spacings: 1 2 3\nkinds: domain domain domain\n") + u8);
    write("nrrd", "float_gzip.nrrd", nrrdHeader(nrrdFields("float", dims, "little", "gzip") + "byte skip: 0\n") + gzipped(f32le));
    write("nrrd", "double_skip.nrrd", nrrdHeader(nrrdFields("double", dims, "big") + "byte skip: -1\nct:=yes\n") + f64be);
    using weft::test::npyDict;
    write("npy", "i2_c.npy", weft::test::npyFile(npyDict("<i2", false, "(2, 3, 4)"), i16le));
    write("npy", "i2_fortran.npy", weft::test::npyFile(npyDict(">i2", true, "(4, 3, 2)"), i16be));
    write("npy", "u1_v2.npy", weft::test::npyFile(npyDict("|u1", false, "(2, 3, 4)"), u8, 2));
    write("npy", "f4.npy", weft::test::npyFile(npyDict("<f4", false, "(2, 3, 4)"), f32le));
    using weft::test::vtkHeader;
    write("vtk", "binary_short.vtk", vtkHeader("BINARY", dims, "short", "SPACING 0.5 1 2\nORIGIN -1 -2 -3\n") + i16be);
    write("vtk", "binary_float.vtk", vtkHeader("BINARY", dims, "float") + [&] {
        std::string be;
        for (int i = 0; i < 24; ++i) appendWord(be, float(i) * 0.25f - 2.0f, true);
        return be;
    }());
    write("vtk", "ascii_uchar.vtk", vtkHeader("ASCII", dims, "unsigned_char", "ASPECT_RATIO 2 2 2\nORIGIN 0 0 1\n") + ascii);
}

weft::Image patternImage(int w, int h, std::vector<std::string> channels) {
    weft::Image img(w, h, std::move(channels));
    for (std::size_t i = 0; i < img.data().size(); ++i) img.data()[i] = float(i % 7) * 0.125f;
    return img;
}

void exrSeeds() {
    const fs::path dir = out / "exr";
    fs::create_directories(dir);
    weft::writeExr(patternImage(4, 4, {"R", "G", "B", "A"}), (dir / "rgba.exr").string(), {{"weft:technique", "volume.raymarch"}});
    weft::writeExr(patternImage(4, 3, {"R", "G", "B", "A", "N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "sampleCount"}),
                   (dir / "aovs.exr").string(), {});
    // A whole frame as one tile: what `weft merge` accepts.
    weft::writeExr(patternImage(4, 4, {"R", "G", "B", "A"}), (dir / "tile1of1.exr").string(),
                   {{"weft:tile", "1/1"}, {"weft:tile:full_resolution", "4x4"}, {"weft:tile:data_window", "0 0 3 3"},
                    {"weft:counter:rays", "16"}, {"weft:complete", "1"}},
                   weft::ImageWindow{0, 0, 4, 4});
    weft::writeExr(patternImage(4, 2, {"R", "G", "B", "A"}), (dir / "tile2of2.exr").string(),
                   {{"weft:tile", "2/2"}, {"weft:tile:full_resolution", "4x4"}, {"weft:complete", "1"}},
                   weft::ImageWindow{0, 2, 4, 4});
}

// Byte 0 picks the parser (tests/fuzz/text_parsers_target.hpp).
void textSeeds() {
    const auto seed = [](int parser, const std::string& name, const std::string& text) {
        write("text", name, std::string(1, char(parser)) + text);
    };
    seed(0, "frames_span", "1001-1100x2");
    seed(0, "frames_list", "1,3,5-9,-5--1");
    seed(0, "frames_down", "10-1x3");
    seed(1, "name_hash", std::string(1, '\2') + "out/frame.#.exr");
    seed(1, "name_at", std::string(1, '\3') + "frame.@@@.exr");
    seed(1, "name_printf", std::string(1, '\1') + "frame.%05d.exr");
    seed(2, "tile", "2/4");
    seed(3, "resolution", "512x512");
    seed(4, "request", "resolution 64x48\ntile 1/2\nframes 1-3\ntechnique volume.raymarch\nset step=0.5\n"
                       "output out.#.exr\nspp 4\nseed 7\nthreads 2\nmax-memory 8\ninput scene.#.json");
    const auto all = weft::techniques().all();
    for (std::size_t i = 0; i < all.size(); ++i) {
        std::string params;
        for (const auto& spec : all[i]->params.specs()) params += (params.empty() ? "" : "\n") + spec.name + "=" + spec.defaultValue;
        seed(5, "params_" + all[i]->name, std::string(1, char(i)) + params);
    }
    seed(6, "raw_options", "256,256,128\n1,1,2.5");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: weft_fuzz_seeds OUT SOURCE\n");
        return 2;
    }
    out = argv[1];
    const fs::path source = argv[2];
    try {
        weft::initVdb();
        sceneSeeds(source);
        vdbSeeds();
        objSeeds(source);
        plySeeds();
        rawSeeds();
        volumeFileSeeds();
        exrSeeds();
        textSeeds();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "weft_fuzz_seeds: %s\n", e.what());
        return 1;
    }
    return 0;
}
