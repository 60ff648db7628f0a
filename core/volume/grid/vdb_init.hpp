#pragma once
// OpenVDB's one-time set-up (grid types, metadata and transforms
// registered), done once per process before a grid is made or a file read.
#include <mutex>

#include <openvdb/openvdb.h>

namespace weft {

// Calls openvdb::initialize() once.
inline void initVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

}  // namespace weft
