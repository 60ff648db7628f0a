// Mesh files: OBJ (+MTL, `t crease`/`t corner` tags) through tinyobjloader,
// which keeps the file's vertex indices so subdivision sees the real
// topology; PLY through Assimp (core/mesh/mesh_codec.hpp). Both are checked after reading: indices in
// range, at least one face, finite positions.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "core/base/error.hpp"
#include "core/base/files/input_file.hpp"
#include "core/mesh/mesh.hpp"
#include "core/mesh/mesh_codec.hpp"

namespace fs = std::filesystem;

namespace weft {

namespace {

// Loader messages may span lines; weft errors are one line.
std::string oneLine(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    return text;
}

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw Error("mesh '" + path + "': " + what); }

constexpr double kMaxAlbedo = 1e3, kMaxEmission = 1e9, kMaxExponent = 1e6;

// MTL values within the ranges shading stays finite in: tinyobjloader reads
// "Ns 1e39" as float infinity, which reached images as NaN.
void checkMtlValue(const std::string& path, const tinyobj::material_t& m, const char* key, double v, double hi) {
    if (std::isfinite(v) && v >= 0 && v <= hi) return;
    char text[160];
    std::snprintf(text, sizeof text, "%s %g is outside [0, %g]", key, v, hi);
    fail(path, "material '" + m.name + "': " + text);
}

Material fromMtl(const std::string& path, const tinyobj::material_t& m) {
    for (int i = 0; i < 3; ++i) {
        checkMtlValue(path, m, "Kd", m.diffuse[i], kMaxAlbedo);
        checkMtlValue(path, m, "Ks", m.specular[i], kMaxAlbedo);
        checkMtlValue(path, m, "Ke", m.emission[i], kMaxEmission);
    }
    checkMtlValue(path, m, "Ns", std::max(0.0f, float(m.shininess)), kMaxExponent);  // a negative exponent reads as 0
    Material out;
    out.name = m.name;
    out.diffuse = Vec3f(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
    out.glossy = Vec3f(m.specular[0], m.specular[1], m.specular[2]);
    out.exponent = std::max(0.0f, float(m.shininess));
    out.emission = Vec3f(m.emission[0], m.emission[1], m.emission[2]);
    return out;
}

void readTags(const tinyobj::mesh_t& mesh, PolyMesh& out) {
    for (const tinyobj::tag_t& tag : mesh.tags) {
        if (tag.name == "crease") {
            for (std::size_t e = 0; e + 1 < tag.intValues.size(); e += 2)
                out.creases.push_back({tag.intValues[e], tag.intValues[e + 1], tag.floatValues.empty() ? 10.0f : float(tag.floatValues[0])});
        } else if (tag.name == "corner") {
            for (std::size_t i = 0; i < tag.intValues.size(); ++i)
                out.corners.emplace_back(tag.intValues[i], i < tag.floatValues.size() ? float(tag.floatValues[i]) : 10.0f);
        }
    }
}

// tinyobjloader reads a coordinate it cannot parse ("inf", "nan", "1,5") as
// 0 without a word, so every vertex line's numbers are checked first.
void checkObjVertexNumbers(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    for (long n = 1; std::getline(in, line); ++n) {
        const char* p = line.c_str();
        while (blank(*p)) ++p;
        if (p[0] != 'v' || !blank(p[1])) continue;
        for (p += 1;;) {
            while (blank(*p)) ++p;
            if (*p == '\0' || *p == '#') break;
            char* end = nullptr;
            const double v = std::strtod(p, &end);
            if (end == p || !(blank(*end) || *end == '\0' || *end == '#') || !std::isfinite(v)) {
                const char* w = p;
                while (*w && !blank(*w)) ++w;
                fail(path, "line " + std::to_string(n) + ": vertex coordinate '" + std::string(p, std::min<std::size_t>(w - p, 40)) +
                               "' is not a finite number");
            }
            p = end;
        }
    }
}

// Material files are inputs like the OBJ: a FIFO named by mtllib blocked
// tinyobjloader's read forever; a missing one is named in weft's words.
void checkMtlFiles(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const fs::path dir = fs::path(path).parent_path();
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::string key;
        if (!(words >> key) || key != "mtllib") continue;
        for (std::string name; words >> name;) {
            const fs::path mtl = dir / name;
            std::error_code ec;
            if (!fs::exists(fs::symlink_status(mtl, ec))) fail(path, "its material file '" + mtl.string() + "' (mtllib) does not exist");
            requireRegularFile(mtl.string(), "material file");
        }
    }
}

PolyMesh readObj(const std::string& path) {
    checkObjVertexNumbers(path);
    checkMtlFiles(path);
    tinyobj::ObjReaderConfig config;
    config.triangulate = false;
    config.vertex_color = false;
    config.mtl_search_path = fs::path(path).parent_path().string();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) fail(path, oneLine(reader.Error().empty() ? "cannot be parsed as OBJ" : reader.Error()));
    if (reader.Warning().find("not found") != std::string::npos) fail(path, oneLine(reader.Warning()));
    PolyMesh out;
    const auto& v = reader.GetAttrib().vertices;
    for (std::size_t i = 0; i + 2 < v.size(); i += 3) out.positions.emplace_back(v[i], v[i + 1], v[i + 2]);
    for (const tinyobj::material_t& m : reader.GetMaterials()) out.materials.push_back(fromMtl(path, m));
    const int fallback = int(out.materials.size());
    bool usesFallback = false;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        std::size_t first = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            const int n = shape.mesh.num_face_vertices[f];
            for (int k = 0; k < n; ++k) out.faceIndices.push_back(shape.mesh.indices[first + k].vertex_index);
            const int mat = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
            usesFallback |= mat < 0;
            out.faceMaterial.push_back(mat < 0 ? fallback : mat);
            out.faceSizes.push_back(n);
            first += std::size_t(n);
        }
        readTags(shape.mesh, out);
    }
    if (usesFallback) out.materials.emplace_back();
    return out;
}

bool isPlyType(const std::string& t) {
    static const char* const kTypes[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double",
                                         "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
    return std::find(std::begin(kTypes), std::end(kTypes), t) != std::end(kTypes);
}

// Element names are words ("vertex", "face", "range_grid"): Assimp's parser
// spun for 20 s on "element 888...+888fHce 2" (found by fuzz_ply).
bool isPlyName(const std::string& name) {
    const auto word = [](char c) { return std::isalnum((unsigned char)c) || c == '_' || c == '-' || c == '.'; };
    return !name.empty() && (std::isalpha((unsigned char)name[0]) || name[0] == '_') && std::all_of(name.begin(), name.end(), word);
}

// One header line against the PLY grammar ("element NAME COUNT",
// "property TYPE NAME", "property list TYPE TYPE NAME", ...).
bool plyHeaderLineOk(const std::string& line, std::uintmax_t fileBytes) {
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") return true;
    if (w[0] == "format") return w.size() == 3 && (w[1] == "ascii" || w[1] == "binary_little_endian" || w[1] == "binary_big_endian");
    // Every element takes at least a byte of the file: a larger count is
    // corrupt, and Assimp would allocate it before reading a byte.
    if (w[0] == "element")
        return w.size() == 3 && isPlyName(w[1]) && w[2].size() <= 19 && w[2].find_first_not_of("0123456789") == std::string::npos &&
               std::stoull(w[2]) <= fileBytes;
    if (w[0] == "property" && w.size() == 3) return isPlyType(w[1]);
    if (w[0] == "property" && w.size() == 5) return w[1] == "list" && isPlyType(w[2]) && isPlyType(w[3]);
    return false;
}

// What the header declares, element by element: Assimp writes past its
// buffers when an element is declared twice or the vertices lack a
// coordinate (found by fuzz_ply), so those are refused too.
struct PlyElements {
    std::map<std::string, std::set<std::string>> properties;  // element -> property names
    std::string current;
    // "" when the line fits the elements so far, else what is wrong.
    std::string add(const std::string& line) {
        std::istringstream words(line);
        std::vector<std::string> w;
        for (std::string word; words >> word;) w.push_back(word);
        if (w.empty() || (w[0] != "element" && w[0] != "property")) return "";
        if (w[0] == "element") {
            current = w[1];
            return properties.emplace(current, std::set<std::string>{}).second ? "" : "declares element '" + quoteless(current) + "' twice";
        }
        if (current.empty()) return "declares a property before any element";
        return properties[current].insert(w.back()).second ? "" : "declares property '" + quoteless(w.back()) + "' twice";
    }
    std::string complete() const {
        const auto v = properties.find("vertex");
        if (v == properties.end()) return "declares no vertex element";
        for (const char* c : {"x", "y", "z"})
            if (!v->second.count(c)) return std::string("declares no vertex property ") + c;
        return "";
    }
    static std::string quoteless(const std::string& s) { return s.size() > 40 ? s.substr(0, 40) + "..." : s; }
};

// Assimp spins on a header cut short and crashes on a malformed property
// declaration: the header must be whole and well formed before it reads.
void checkPlyHeader(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    if (!std::getline(in, line) || line.rfind("ply", 0) != 0) fail(path, "is not a PLY file (no 'ply' on its first line)");
    PlyElements elements;
    for (int n = 0; n < 10000 && std::getline(in, line); ++n) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line == "end_header") {
            if (const std::string bad = elements.complete(); !bad.empty()) fail(path, "its PLY header " + bad);
            return;
        }
        if (in.eof()) break;  // a last line without its newline: the file is cut short
        if (!plyHeaderLineOk(line, fs::file_size(path))) fail(path, "PLY header line " + std::to_string(n + 2) + " is malformed");
        if (const std::string bad = elements.add(line); !bad.empty())
            fail(path, "PLY header line " + std::to_string(n + 2) + " " + bad);
    }
    fail(path, "its PLY header has no end_header line (the file is cut short or not PLY)");
}

PolyMesh readPly(const std::string& path) {
    checkPlyHeader(path);
    PolyMesh out;
    std::vector<float> xyz;
    if (const std::string error = meshCodec().readPly(path, xyz, out.faceSizes, out.faceIndices); !error.empty()) fail(path, oneLine(error));
    for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) out.positions.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
    out.materials.emplace_back();
    out.faceMaterial.assign(out.faceSizes.size(), 0);
    return out;
}

void validate(const PolyMesh& mesh, const std::string& path) {
    if (mesh.faceSizes.empty()) fail(path, "has no faces");
    for (const Vec3f& p : mesh.positions)
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) fail(path, "has a vertex position that is not finite");
    const int n = int(mesh.positions.size());
    for (int i : mesh.faceIndices)
        if (i < 0 || i >= n) fail(path, "a face refers to vertex " + std::to_string(i) + " but the file has " + std::to_string(n) + " vertices");
    for (const Crease& c : mesh.creases)
        if (c.v0 < 0 || c.v0 >= n || c.v1 < 0 || c.v1 >= n) fail(path, "a crease refers to a vertex outside the mesh");
    for (const auto& [v, s] : mesh.corners)
        if (v < 0 || v >= n) fail(path, "a corner refers to a vertex outside the mesh");
}

std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace

PolyMesh readPolyMesh(const std::string& path) {
    requireRegularFile(path, "mesh");
    const std::string ext = lowerExtension(path);
    PolyMesh mesh;
    if (ext == ".obj") mesh = readObj(path);
    else if (ext == ".ply") mesh = readPly(path);
    else fail(path, "unknown mesh format '" + ext + "' (known: .obj|.ply)");
    validate(mesh, path);
    return mesh;
}

}  // namespace weft
