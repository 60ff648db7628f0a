#include "oracles/oracle_cache.hpp"

#include <utility>

#include "core/base/shared_cache.hpp"
#include "core/volume/volume_key.hpp"

namespace weft {

namespace {

SharedCache<OracleField>& cache() {
    static SharedCache<OracleField> entries(kOracleCacheEntries);
    return entries;
}

std::string keyOf(const OracleInfo& oracle, const OracleContext& ctx) {
    std::string key = oracle.name + "|" + volumeKey(ctx.volume);
    addKeyNumber(key, ctx.sliceSpacing), addKeyNumber(key, ctx.lmax), addKeyNumber(key, ctx.epsilon);
    return key;
}

}  // namespace

SharedOracleField sharedOracleField(const OracleInfo& oracle, const OracleContext& ctx) {
    auto found = cache().get(keyOf(oracle, ctx), [&] { return oracle.build(ctx); }, {keptGrid(ctx.volume)});
    return {std::move(found.value), found.reused};
}

void clearOracleCache() { cache().clear(); }

}  // namespace weft
