#include "oracles/oracle_cache.hpp"

#include <list>
#include <mutex>

#include "core/volume/volume_key.hpp"

namespace weft {

namespace {

struct Entry {
    std::string key;
    OracleField field;
    openvdb::FloatGrid::ConstPtr keptGrid;  // a volume identified by its tree stays alive, so its address is not reused
};

std::mutex gMutex;
std::list<Entry> gEntries;  // most recently used first

std::string keyOf(const OracleInfo& oracle, const OracleContext& ctx) {
    std::string key = oracle.name + "|" + volumeKey(ctx.volume);
    addKeyNumber(key, ctx.sliceSpacing), addKeyNumber(key, ctx.lmax), addKeyNumber(key, ctx.epsilon);
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
    gEntries.push_front({key, field, keptGrid(ctx.volume)});
    while (gEntries.size() > std::size_t(kOracleCacheEntries)) gEntries.pop_back();
    return {field, false};
}

void clearOracleCache() {
    std::lock_guard<std::mutex> lock(gMutex);
    gEntries.clear();
}

}  // namespace weft
