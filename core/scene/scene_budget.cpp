#include "core/scene/scene_budget.hpp"

#include <cstdio>
#include <filesystem>

#include "core/base/error.hpp"
#include "core/base/input_file.hpp"
#include "core/volume/vdb_preflight.hpp"

namespace weft {

namespace {

// A leaf holds 8^3 values, its masks and node bookkeeping.
constexpr double kLeafValues = 512, kLeafOverhead = 160;
// An OBJ or PLY byte becomes at most this many bytes of triangles, indices
// and BVH once loaded (an ASCII vertex line of ~30 bytes: 12 bytes of
// position; a binary PLY triangle of 13 bytes: ~110 bytes with its BVH node).
constexpr double kMeshBytesPerFileByte = 10;

}  // namespace

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
