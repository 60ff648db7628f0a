#include "core/scene/scene_budget.hpp"

#include <cstdio>
#include <filesystem>
#include <set>

#include "core/base/error.hpp"
#include "core/base/files/input_file.hpp"
#include "core/volume/io/vdb_preflight.hpp"

namespace weft {

namespace {

// A leaf holds 8^3 values, its masks and node bookkeeping.
constexpr double kLeafValues = 512, kLeafOverhead = 160;
// An OBJ or PLY byte becomes at most this many bytes of triangles, indices
// and BVH once loaded (an ASCII vertex line of ~30 bytes: 12 bytes of
// position; a binary PLY triangle of 13 bytes: ~110 bytes with its BVH node).
constexpr double kMeshBytesPerFileByte = 10;

// Ignores what it cannot estimate: the loader then reports it with its position.
template <class F>
double estimateOrZero(F&& estimate) {
    try {
        return estimate();
    } catch (const std::exception&) {
        return 0;
    }
}

}  // namespace

double sceneFileLoadBytes(const nlohmann::json& root, const std::function<std::string(const std::string&)>& volumeFile,
                          const std::function<std::string(const std::string&)>& meshFile) {
    namespace fs = std::filesystem;
    double bytes = 0;
    std::set<std::string> files;
    if (root.contains("volumes") && root["volumes"].is_array())
        for (const nlohmann::json& v : root["volumes"]) {
            if (v.contains("file") && v["file"].is_string()) {
                const std::string file = volumeFile(v["file"].get<std::string>());
                std::error_code ec;
                if (files.insert(fs::weakly_canonical(file, ec).string()).second) bytes += estimateOrZero([&] { return vdbLoadBytes(file); });
            } else if (v.contains("procedural") && v["procedural"].is_string()) {
                const int res = v.contains("resolution") && v["resolution"].is_number() ? int(v["resolution"].get<double>()) : 128;
                bytes += proceduralLoadBytes(res, v["procedural"].get<std::string>());
            }
        }
    if (root.contains("meshes") && root["meshes"].is_array())
        for (const nlohmann::json& m : root["meshes"])
            if (m.contains("file") && m["file"].is_string())
                bytes += estimateOrZero([&] { return meshLoadBytes(meshFile(m["file"].get<std::string>())); });
    return bytes;
}

double vdbLoadBytes(const std::string& path) {
    requireRegularFile(path, "volume");
    const std::shared_ptr<const VdbLayout> layout = preflightVdb(path);
    double bytes = 0;
    for (const auto& [name, grid] : layout->grids)
        bytes += double(grid.leaves.size()) * (kLeafValues * sizeof(float) * grid.components + kLeafOverhead);
    return bytes;
}

double meshLoadBytes(const std::string& path) {
    requireRegularFile(path, "mesh");
    return kMeshBytesPerFileByte * double(std::filesystem::file_size(path));
}

double proceduralLoadBytes(int res, const std::string& kind) {
    const double voxels = double(res) * res * res;
    return voxels * sizeof(float) * (kind == "fire" ? 2 : 1);
}

void requireLoadWithin(double bytes, double limitBytes, const std::string& what) {
    if (!(limitBytes > 0) || bytes <= limitBytes) return;
    const double gib = double(1 << 30);
    char text[256];
    std::snprintf(text, sizeof text,
                  " needs about %.3g GiB to load (estimated from its files before reading them), above the %.3g GiB limit "
                  "(--max-memory GiB; the default is 3/4 of physical memory)",
                  bytes / gib, limitBytes / gib);
    throw Error(what + text);
}

}  // namespace weft
