#pragma once
// Oracle fields shared between renders of one process. A frame sequence of a
// static volume and the runs of a sweep ask for the same field again and
// again; building it (a pass over every voxel and a distance transform) can
// cost a third of an adaptive render, so it is built once per (oracle,
// volume, transfer function, spacing, lmax, epsilon).
//
// The volume is known by core/volume/volume_key.hpp's key (its file or its
// tree, transform, transfer function, emission and box).
#include "oracles/oracle.hpp"

namespace weft {

struct SharedOracleField {
    OracleField field;
    bool reused = false;  // found in the cache, not built by this call
};

// The field `oracle` builds for ctx, from the cache when an equal request was
// built before. Thread-safe; the last kOracleCacheEntries fields are kept.
SharedOracleField sharedOracleField(const OracleInfo& oracle, const OracleContext& ctx);

constexpr int kOracleCacheEntries = 4;

// Empties the cache (tests).
void clearOracleCache();

}  // namespace weft
