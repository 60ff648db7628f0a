#pragma once
// Chebyshev distances to a mask's voxels, up to a few rings, for the
// oracles' sampling-distance fields (feature_distance.hpp). The cube of
// radius k is the product of three intervals, so growing a set by one ring
// is three separable ORs of shifted bit rows; over a dense box of bits that
// costs a few word operations per 64 voxels, where growing a sparse tree
// ring by ring (the fallback for boxes too large to hold densely) allocates
// and walks every leaf again on each ring.
#include <cstdint>
#include <optional>
#include <vector>

#include <openvdb/openvdb.h>

namespace weft {

// Per voxel of `box`: 0 on the mask, k (1..rings) at Chebyshev distance k,
// kBeyond past `rings`. Empty when the box holds more than maxVoxels.
struct RingDistances {
    static constexpr std::uint8_t kBeyond = 255;
    openvdb::CoordBBox box;
    std::vector<std::uint8_t> ring;  // x fastest, then y, then z
    std::uint8_t at(const openvdb::Coord& c) const {
        const openvdb::Coord d = box.dim(), o = c - box.min();
        return ring[(std::size_t(o.z()) * d.y() + o.y()) * d.x() + o.x()];
    }
};

// The mask's active voxels grown by `rings` (at most 254) inside the box of
// those voxels padded by `rings`; nullopt when that box is empty or holds
// more than maxVoxels voxels.
std::optional<RingDistances> chebyshevRings(const openvdb::MaskTree& mask, int rings, std::size_t maxVoxels);

}  // namespace weft
