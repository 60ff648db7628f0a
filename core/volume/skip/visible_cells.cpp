#include "core/volume/skip/visible_cells.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bitset>
#include <cmath>
#include <limits>
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/volume/grid/leaf_region.hpp"
#include "core/volume/grid/tiles_where.hpp"

namespace weft {

namespace {

using Leaf = openvdb::FloatTree::LeafNodeType;
constexpr int kSpan = 10;  // a leaf's voxels and one more on each side
constexpr int kCells = 9;  // cells whose low corner lies in [origin - 1, origin + 7]
using CellBits = std::bitset<kCells * kCells * kCells>;

// The visible cells of one leaf's neighbourhood: the leaf's values and the
// one-voxel apron around it, read from the 26 neighbouring regions' buffers
// (a tree lookup per neighbour, not per apron voxel). Each value is the
// range [lo, hi] a cell's interpolation can reach from it: itself, or
// everything for a non-finite value (lookup reads NaN as the table's start).
// A cell's range joins its eight corners', one axis at a time, as runs of
// minima and maxima over separate arrays (so they vectorise).
CellBits visibleCellsOf(const Leaf& leaf, const openvdb::FloatGrid::ConstAccessor& acc, const TransferFunction& tf) {
    constexpr float kInf = std::numeric_limits<float>::infinity();
    struct Scratch {
        std::array<float, kSpan * kSpan * kSpan> lo, hi;    // per block voxel
        std::array<float, kSpan * kSpan * kCells> zlo, zhi;  // joined along z
        std::array<float, kSpan * kCells * kCells> ylo, yhi; // and along y
    };
    static thread_local Scratch m;
    LeafRegion<float> regions[3][3][3];
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz)
                regions[dx + 1][dy + 1][dz + 1] = LeafRegion<float>::of(acc, leaf.origin().offsetBy(8 * dx, 8 * dy, 8 * dz));
    // Block index 0..9 on an axis is voxel -1..8 of the leaf: region 0, 1 or 2 and the offset in it.
    // A block row along z is the last voxel of the region below, eight of the leaf's row, the first of the region above.
    const auto regionOf = [](int b) { return b == 0 ? 0 : b == kSpan - 1 ? 2 : 1; };
    const auto offsetIn = [](int b) { return (b + 7) & 7; };
    float* values = m.hi.data();  // the raw values first, then each one's range below
    for (int x = 0; x < kSpan; ++x)
        for (int y = 0; y < kSpan; ++y) {
            const LeafRegion<float>* r = regions[regionOf(x)][regionOf(y)];
            const int base = offsetIn(x) << 6 | offsetIn(y) << 3;
            float* row = values + (x * kSpan + y) * kSpan;
            row[0] = r[0].at(base | 7);
            if (r[1].data) std::copy(r[1].data + base, r[1].data + base + 8, row + 1);
            else std::fill(row + 1, row + 9, r[1].constant);
            row[kSpan - 1] = r[2].at(base);
        }
    float allLo = kInf, allHi = -kInf;
    for (int i = 0; i < kSpan * kSpan * kSpan; ++i) {
        const float v = values[i];
        const bool finite = v - v == 0.0f;  // false for NaN and +-Inf
        m.lo[i] = finite ? v : -kInf, m.hi[i] = finite ? v : kInf;
    }
    for (int i = 0; i < kSpan * kSpan * kSpan; ++i) allLo = std::min(allLo, m.lo[i]), allHi = std::max(allHi, m.hi[i]);
    CellBits visible;
    if (tf.transparentOver(allLo, allHi)) return visible;  // the common case far from the features
    for (int xy = 0; xy < kSpan * kSpan; ++xy)
        for (int z = 0; z < kCells; ++z) {
            const int i = xy * kSpan + z, o = xy * kCells + z;
            m.zlo[o] = std::min(m.lo[i], m.lo[i + 1]), m.zhi[o] = std::max(m.hi[i], m.hi[i + 1]);
        }
    for (int x = 0; x < kSpan; ++x)
        for (int y = 0; y < kCells; ++y)
            for (int z = 0; z < kCells; ++z) {
                const int i = (x * kSpan + y) * kCells + z, o = (x * kCells + y) * kCells + z;
                m.ylo[o] = std::min(m.zlo[i], m.zlo[i + kCells]), m.yhi[o] = std::max(m.zhi[i], m.zhi[i + kCells]);
            }
    for (int x = 0; x < kCells; ++x)
        for (int yz = 0; yz < kCells * kCells; ++yz) {
            const int i = x * kCells * kCells + yz;
            const float lo = std::min(m.ylo[i], m.ylo[i + kCells * kCells]), hi = std::max(m.yhi[i], m.yhi[i + kCells * kCells]);
            if (!tf.transparentOver(lo, hi)) visible.set(std::size_t(i));
        }
    return visible;
}

// Offset 0 or 8 on each axis, one of a leaf's eight corners by the bits of `a`.
openvdb::Coord cornerStep(int a) { return openvdb::Coord(8 * (a & 1), 8 * ((a >> 1) & 1), 8 * ((a >> 2) & 1)); }

// The output leaf at `origin` (active on its visible cells; made without a
// value buffer, whose 2 KiB allocation and fill were most of the pass): the cells of
// the up to eight grid leaves at origin + 8 {0,1}^3 that fall in it. Leaf
// D's cells start at D - 1, so its cells 1..8 lie in leaf D and cell 0 in
// the leaf below it along that axis.
std::unique_ptr<Leaf> outputLeaf(const openvdb::Coord& origin, const std::unordered_map<openvdb::Coord, std::size_t>& indexOf,
                                 const std::vector<CellBits>& visible) {
    std::unique_ptr<Leaf> leaf;
    for (int a = 0; a < 8; ++a) {
        const openvdb::Coord step = cornerStep(a);
        const auto found = indexOf.find(origin + step);
        if (found == indexOf.end() || visible[found->second].none()) continue;
        const CellBits& cells = visible[found->second];
        // Cells of this source inside the output leaf, per axis: [1, 9) or [0, 1).
        const openvdb::Coord lo(step.x() ? 0 : 1, step.y() ? 0 : 1, step.z() ? 0 : 1);
        const openvdb::Coord hi(step.x() ? 1 : kCells, step.y() ? 1 : kCells, step.z() ? 1 : kCells);
        for (int x = lo.x(); x < hi.x(); ++x)
            for (int y = lo.y(); y < hi.y(); ++y)
                for (int z = lo.z(); z < hi.z(); ++z) {
                    if (!cells.test((x * kCells + y) * kCells + z)) continue;
                    if (!leaf) leaf = std::make_unique<Leaf>(openvdb::PartialCreate(), origin, 0.0f, false);
                    leaf->setActiveState(Leaf::coordToOffset(step + openvdb::Coord(x - 1, y - 1, z - 1)), true);
                }
    }
    return leaf;
}

}  // namespace

openvdb::FloatGrid::Ptr visibleCells(const openvdb::FloatGrid& grid, const TransferFunction& tf) {
    if (!tf.transparentOver(grid.background(), grid.background())) return nullptr;
    auto cells = openvdb::FloatGrid::create(0.0f);
    cells->setTransform(openvdb::math::Transform::createLinearTransform(1.0));
    std::vector<const Leaf*> leaves;
    leaves.reserve(grid.tree().leafCount());
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) leaves.push_back(leaf.getLeaf());
    std::vector<CellBits> visible(leaves.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 64), [&](const tbb::blocked_range<std::size_t>& range) {
        const openvdb::FloatGrid::ConstAccessor acc = grid.getConstAccessor();
        for (std::size_t i = range.begin(); i != range.end(); ++i) visible[i] = visibleCellsOf(*leaves[i], acc, tf);
    });
    // The output leaves are made in parallel from the cells of the grid
    // leaves over them (one tree write per cell was most of the time).
    std::unordered_map<openvdb::Coord, std::size_t> indexOf;
    std::vector<openvdb::Coord> origins;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        if (visible[i].none()) continue;
        indexOf.emplace(leaves[i]->origin(), i);
        for (int a = 0; a < 8; ++a) origins.push_back(leaves[i]->origin() - cornerStep(a));
    }
    std::sort(origins.begin(), origins.end());
    origins.erase(std::unique(origins.begin(), origins.end()), origins.end());
    std::vector<std::unique_ptr<Leaf>> made(origins.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, origins.size(), 64), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) made[i] = outputLeaf(origins[i], indexOf, visible);
    });
    for (auto& leaf : made)
        if (leaf) cells->tree().addLeaf(leaf.release());
    // Tiles hold one value: a visible one marks its box and, for the cells
    // that straddle into it from below, one voxel more on the low sides.
    // Filled after the leaves, which it may cover: the union either way.
    const auto visibleTile = [&](float v) { return !tf.transparentOver(v, v); };  // a non-finite value is visible, as a voxel's
    for (const openvdb::CoordBBox& box : tilesWhere(grid.tree(), false, visibleTile))
        cells->tree().fill(openvdb::CoordBBox(box.min().offsetBy(-1), box.max()), 1.0f, true);
    return cells;
}

}  // namespace weft
