#include "oracles/oracle_cache.hpp"

#include <cstdio>
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
