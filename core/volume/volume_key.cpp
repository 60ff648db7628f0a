#include "core/volume/volume_key.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace weft {

namespace {

namespace fs = std::filesystem;

// The emission grid by its content: it is built from the temperature and
// emission grids (possibly of other files) and the scene's emission
// settings, so its values are what derived work depends on. One pass,
// eight bytes per step.
std::uint64_t emissionHash(const openvdb::Vec3SGrid& grid) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    auto mix = [&](const void* data, std::size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < bytes; i += 8) {
            std::uint64_t word = 0;
            std::memcpy(&word, p + i, std::min<std::size_t>(8, bytes - i));
            h = (h ^ word) * 0x100000001b3ull;
            h ^= h >> 29;
        }
    };
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        const openvdb::Coord origin = leaf->origin();
        mix(&origin, sizeof origin);
        mix(leaf->buffer().data(), sizeof(openvdb::Vec3s) * leaf->SIZE);
        mix(&leaf->getValueMask(), sizeof(leaf->getValueMask()));
    }
    for (auto tile = grid.tree().cbeginValueOn(); tile; ++tile) {
        if (tile.isVoxelValue()) continue;
        const openvdb::Coord c = tile.getCoord();
        const openvdb::Vec3s v = *tile;
        mix(&c, sizeof c), mix(&v, sizeof v);
    }
    return h;
}

// Whether the volume is identified by its file (else by its tree).
bool identifiedByFile(const Volume& v) {
    std::error_code ec;
    return !v.source.empty() && fs::is_regular_file(v.source, ec);
}

}  // namespace

void addKeyNumber(std::string& key, double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g|", value);
    key += text;
}

std::string volumeKey(const Volume& v) {
    std::string key;
    if (identifiedByFile(v)) {
        std::error_code ec;
        key += "file:" + v.source + "|" + v.name + "|";
        addKeyNumber(key, double(fs::file_size(v.source, ec)));
        addKeyNumber(key, double(fs::last_write_time(v.source, ec).time_since_epoch().count()));
    } else {
        char text[32];
        std::snprintf(text, sizeof text, "tree:%p|", static_cast<const void*>(&v.grid->constTree()));
        key += text;
    }
    const openvdb::math::Mat4d m = v.grid->transform().baseMap()->getAffineMap()->getMat4();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) addKeyNumber(key, m(i, j));
    addKeyNumber(key, v.tf.rangeMin()), addKeyNumber(key, v.tf.rangeMax());
    for (const TfPoint& p : v.tf.points()) {
        addKeyNumber(key, p.s), addKeyNumber(key, p.extinction);
        for (double c : p.color) addKeyNumber(key, c);
    }
    if (v.emission) {
        char text[40];
        std::snprintf(text, sizeof text, "emission:%016llx|", static_cast<unsigned long long>(emissionHash(*v.emission)));
        key += text;
    }
    const openvdb::CoordBBox box = v.indexBox();
    for (int a = 0; a < 3; ++a) addKeyNumber(key, box.min()[a]), addKeyNumber(key, box.max()[a]);
    return key;
}

openvdb::FloatGrid::ConstPtr keptGrid(const Volume& volume) { return identifiedByFile(volume) ? nullptr : volume.grid; }

}  // namespace weft
