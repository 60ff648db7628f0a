#pragma once
// Where a trilinear lookup of a grid can be seen through its transfer
// function. A lookup inside cell c (the 2x2x2 voxels c + {0,1}^3)
// interpolates its eight corner values, so it lies between their minimum
// and maximum; where the transfer function's table is zero over that whole
// range (TransferFunction::transparentOver), every lookup in the cell has
// zero extinction, and marching past the cell changes no pixel. This is
// VTK's min-max space leaping at the finest granularity, on the grid's own
// leaves: inactive voxels and tiles are tested by their values too, so a
// transparent active voxel is skipped and a visible inactive one is not.
#include <openvdb/openvdb.h>

#include <climits>

#include "core/volume/grid/leaf_sampler.hpp"
#include "core/volume/optics/transfer_function.hpp"

namespace weft {

// An index-space grid (voxel size 1) whose active voxels are the low
// corners c of the cells that may be visible; null where the background
// itself is visible, so that nothing may be skipped. Only its topology
// means anything: its leaves are made without value buffers, so its
// values are not defined (read as 0 where no buffer was ever made).
openvdb::FloatGrid::Ptr visibleCells(const openvdb::FloatGrid& grid, const TransferFunction& tf);

// Whether the cell holding an index-space point is one of visibleCells':
// a bit of its leaf's value mask (or its tile's state), the last leaf kept,
// so a march can pass over a hidden cell for a few instructions instead of
// a lookup (an HDDA leaf interval is mostly hidden cells on thin features).
// One per thread, like the accessor it reads through.
class VisibleCellTest {
public:
    explicit VisibleCellTest(const openvdb::FloatGrid& cells) : acc_(cells.getConstAccessor()) {}
    bool operator()(const openvdb::Vec3d& p) {
        const int ix = floorToInt(p.x()), iy = floorToInt(p.y()), iz = floorToInt(p.z());
        const openvdb::Coord origin(ix & ~7, iy & ~7, iz & ~7);
        if (origin != origin_) moveTo(origin);
        return mask_ ? mask_->isOn((ix & 7) << 6 | (iy & 7) << 3 | (iz & 7)) : tileOn_;
    }

private:
    void moveTo(const openvdb::Coord& origin) {
        origin_ = origin;
        const auto* leaf = acc_.probeConstLeaf(origin);
        mask_ = leaf ? &leaf->getValueMask() : nullptr;
        tileOn_ = !leaf && acc_.isValueOn(origin);
    }

    openvdb::FloatGrid::ConstAccessor acc_;
    openvdb::Coord origin_{INT_MAX, INT_MAX, INT_MAX};  // no leaf origin: those are multiples of 8
    const openvdb::util::NodeMask<3>* mask_ = nullptr;
    bool tileOn_ = false;
};

}  // namespace weft
