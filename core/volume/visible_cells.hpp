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

#include "core/volume/transfer_function.hpp"

namespace weft {

// An index-space grid (voxel size 1) whose active voxels are the low
// corners c of the cells that may be visible; null where the background
// itself is visible, so that nothing may be skipped.
openvdb::FloatGrid::Ptr visibleCells(const openvdb::FloatGrid& grid, const TransferFunction& tf);

}  // namespace weft
