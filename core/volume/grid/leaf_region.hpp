#pragma once
// One 8^3 region of a grid, as a march reads it: a leaf's values, or the
// one tile (or background) value covering the region where there is no
// leaf. A tree lookup per region instead of one per voxel.
#include <openvdb/openvdb.h>

namespace weft {

template <class Value>
struct LeafRegion {
    const Value* data = nullptr;
    Value constant = openvdb::zeroVal<Value>();
    Value at(int offset) const { return data ? data[offset] : constant; }  // offset: LeafNode::coordToOffset

    // The region whose leaf origin is `origin` (a multiple of 8 on each axis).
    template <class Accessor>
    static LeafRegion of(const Accessor& acc, const openvdb::Coord& origin) {
        LeafRegion r;
        if (const auto* leaf = acc.probeConstLeaf(origin)) r.data = leaf->buffer().data();
        else r.constant = acc.getValue(origin);
        return r;
    }
};

}  // namespace weft
