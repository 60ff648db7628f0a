#include "oracles/oracle_cache.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <list>
#include <mutex>

namespace weft {

namespace {

namespace fs = std::filesystem;

struct Entry {
    std::string key;
    OracleField field;
    openvdb::FloatGrid::ConstPtr keptGrid;  // a volume identified by its tree stays alive, so its address is not reused
};

std::mutex gMutex;
std::list<Entry> gEntries;  // most recently used first

void addNumber(std::string& key, double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g|", v);
    key += text;
}

// The emission grid by its content: it is built from the temperature and
// emission grids (possibly of other files) and the scene's emission
// settings, so its values are what an oracle depends on. One pass, eight
// bytes per step.
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

std::string keyOf(const OracleInfo& oracle, const OracleContext& ctx) {
    const Volume& v = ctx.volume;
    std::string key = oracle.name + "|";
    if (identifiedByFile(v)) {
        std::error_code ec;
        key += "file:" + v.source + "|" + v.name + "|";
        addNumber(key, double(fs::file_size(v.source, ec)));
        addNumber(key, double(fs::last_write_time(v.source, ec).time_since_epoch().count()));
    } else {
        char text[32];
        std::snprintf(text, sizeof text, "tree:%p|", static_cast<const void*>(&v.grid->constTree()));
        key += text;
    }
    const openvdb::math::Mat4d m = v.grid->transform().baseMap()->getAffineMap()->getMat4();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) addNumber(key, m(i, j));
    addNumber(key, v.tf.rangeMin()), addNumber(key, v.tf.rangeMax());
    for (const TfPoint& p : v.tf.points()) {
        addNumber(key, p.s), addNumber(key, p.extinction);
        for (double c : p.color) addNumber(key, c);
    }
    if (v.emission) {
        char text[40];
        std::snprintf(text, sizeof text, "emission:%016llx|", static_cast<unsigned long long>(emissionHash(*v.emission)));
        key += text;
    }
    // The field grows as far as the volume's box, which a moving volume's
    // reach pads (the same file under another shutter: another field).
    const openvdb::CoordBBox box = v.indexBox();
    for (int a = 0; a < 3; ++a) addNumber(key, box.min()[a]), addNumber(key, box.max()[a]);
    addNumber(key, ctx.sliceSpacing), addNumber(key, ctx.lmax), addNumber(key, ctx.epsilon);
    return key;
}

}  // namespace

SharedOracleField sharedOracleField(const OracleInfo& oracle, const OracleContext& ctx) {
    const std::string key = keyOf(oracle, ctx);
    {
        std::lock_guard<std::mutex> lock(gMutex);
        for (auto it = gEntries.begin(); it != gEntries.end(); ++it)
            if (it->key == key) {
                gEntries.splice(gEntries.begin(), gEntries, it);
                return {it->field, true};
            }
    }
    // Built outside the lock: two renders that miss at once both build (the same field).
    OracleField field = oracle.build(ctx);
    std::lock_guard<std::mutex> lock(gMutex);
    gEntries.push_front({key, field, identifiedByFile(ctx.volume) ? nullptr : ctx.volume.grid});
    while (gEntries.size() > std::size_t(kOracleCacheEntries)) gEntries.pop_back();
    return {field, false};
}

void clearOracleCache() {
    std::lock_guard<std::mutex> lock(gMutex);
    gEntries.clear();
}

}  // namespace weft
