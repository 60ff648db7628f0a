#pragma once
// A dense grid's values as one array over its active box (one voxel wider,
// so a cell on the box's edge finds all eight corners in it): a trilinear
// lookup is eight loads at fixed strides, with no leaf to find and no cell
// straddling two leaves (a third of all cells). It costs 4 bytes per voxel
// of the box, so it is built only where the leaves fill at least an eighth
// of the box and the box holds at most 2^25 voxels (128 MB); other grids
// keep their tree. The values are the grid's own (copyToDense reads tiles
// and inactive voxels as getValue does), so lookups through it equal the
// leaf path's bit for bit. The array lies on huge pages (large_buffer.hpp):
// on a virtual machine, faulting in tens of megabytes 4 KiB at a time cost
// more than copying the values.
#include <cstddef>
#include <memory>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include "core/base/memory/large_buffer.hpp"

namespace weft {

template <class GridT>
class DenseCopy {
public:
    using Value = typename GridT::ValueType;

    // Null where the box holds more than maxVoxels voxels or the grid's
    // leaves fill less than an eighth of it.
    static std::unique_ptr<const DenseCopy> of(const GridT& grid, std::size_t maxVoxels = std::size_t(1) << 25) {
        openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
        if (box.empty()) return nullptr;
        box.expand(1);
        const double voxels = double(box.dim().x()) * box.dim().y() * box.dim().z();
        if (voxels > double(maxVoxels) || 8.0 * double(grid.tree().leafCount()) * 512.0 < voxels) return nullptr;
        auto copy = std::unique_ptr<DenseCopy>(new DenseCopy(box));
        openvdb::tools::copyToDense(grid, copy->dense_);
        return copy;
    }

    // Whether the cell with low corner (x, y, z) has its eight corners here.
    bool holdsCell(int x, int y, int z) const {
        return unsigned(x - lo_.x()) < cells_[0] && unsigned(y - lo_.y()) < cells_[1] && unsigned(z - lo_.z()) < cells_[2];
    }
    // The cell's corner values, v[dx][dy][dz]; only where holdsCell.
    void cell(int x, int y, int z, Value (&v)[2][2][2]) const {
        const Value* d = dense_.data() + (std::size_t(x - lo_.x()) * xStride_ + std::size_t(y - lo_.y()) * yStride_ + (z - lo_.z()));
        v[0][0][0] = d[0], v[0][0][1] = d[1], v[0][1][0] = d[yStride_], v[0][1][1] = d[yStride_ + 1];
        const Value* e = d + xStride_;
        v[1][0][0] = e[0], v[1][0][1] = e[1], v[1][1][0] = e[yStride_], v[1][1][1] = e[yStride_ + 1];
    }

private:
    explicit DenseCopy(const openvdb::CoordBBox& box)
        : storage_(std::size_t(box.volume())), dense_(box, storage_.data()), lo_(box.min()), xStride_(dense_.xStride()),
          yStride_(dense_.yStride()) {
        for (int a = 0; a < 3; ++a) cells_[a] = unsigned(box.dim()[a] - 1);
    }

    FreshBuffer<Value> storage_;                                    // dense_'s values, filled by copyToDense
    openvdb::tools::Dense<Value, openvdb::tools::LayoutZYX> dense_;  // z fastest
    openvdb::Coord lo_;
    std::size_t xStride_, yStride_;
    unsigned cells_[3];  // cells per axis: one fewer than voxels
};

}  // namespace weft
