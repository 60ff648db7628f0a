#pragma once
// Trilinear lookups of a float (or Vec3s) grid: openvdb::tools::BoxSampler's eight
// values and interpolation order (z, then y, then x), in float arithmetic,
// with the values read straight from the leaves that hold them. The leaf of
// the last lookup and, once a cell straddles into them, its seven
// neighbours (+8 in x, y, z) are kept: a ray's consecutive samples mostly
// stay in one 8^3 leaf, and the accessor's eight getValue calls per sample,
// with BoxSampler's double-precision weights, were most of a march's time.
// Results differ from BoxSampler's by float rounding only (a few ulps of
// the values' range). One sampler per thread, like the accessor it reads through.
#include <climits>
#include <cmath>

#include <openvdb/openvdb.h>

#include "core/volume/grid/dense_copy.hpp"
#include "core/volume/grid/leaf_region.hpp"

namespace weft {

// std::floor is a libm call on baseline x86-64 (no SSE4.1 round);
// truncation and a compare are not. Callers' points lie inside grids
// (index +-2^30), well within int.
inline int floorToInt(double x) {
    const int i = int(x);
    return i - (x < double(i));
}

template <class GridT>
class BasicLeafSampler {
public:
    using Accessor = typename GridT::ConstAccessor;
    using Value = typename GridT::ValueType;

    // Reads through `accessor` and maps world points with `transform`; both must outlive the sampler.
    BasicLeafSampler(const Accessor& accessor, const openvdb::math::Transform& transform) : acc_(&accessor), xf_(&transform) {}

    // At an index-space point.
    Value isSample(const openvdb::Vec3d& p) {
        const int ix = floorToInt(p.x()), iy = floorToInt(p.y()), iz = floorToInt(p.z());
        const double fx = ix, fy = iy, fz = iz;
        Value v[2][2][2];
        if (dense_ && dense_->holdsCell(ix, iy, iz)) {
            dense_->cell(ix, iy, iz, v);
            return trilinear(v, float(p.x() - fx), float(p.y() - fy), float(p.z() - fz));
        }
        const openvdb::Coord origin(ix & ~7, iy & ~7, iz & ~7);
        if (origin != origin_) moveTo(origin);
        const int lx = ix & 7, ly = iy & 7, lz = iz & 7;
        if (lx != 7 && ly != 7 && lz != 7) fromLeaf(lx << 6 | ly << 3 | lz, v);
        else fromBlock(lx, ly, lz, v);  // the cell straddles leaves
        return trilinear(v, float(p.x() - fx), float(p.y() - fy), float(p.z() - fz));
    }
    // Reads cells inside `dense` (the same grid's copy; it must outlive the
    // sampler) from it, the others from the leaves.
    void useDense(const DenseCopy<GridT>* dense) { dense_ = dense; }
    // At a world-space point.
    Value wsSample(const openvdb::Vec3d& p) { return isSample(xf_->worldToIndex(p)); }

private:
    using Region = LeafRegion<Value>;

    static Value lerp(const Value& a, const Value& b, float w) { return a + (b - a) * w; }
    static Value trilinear(const Value (&v)[2][2][2], float u, float s, float t) {
        return lerp(lerp(lerp(v[0][0][0], v[0][0][1], t), lerp(v[0][1][0], v[0][1][1], t), s),
                    lerp(lerp(v[1][0][0], v[1][0][1], t), lerp(v[1][1][0], v[1][1][1], t), s), u);
    }

    void moveTo(const openvdb::Coord& origin) {
        origin_ = origin;
        region_[0] = probe(origin);
        probed_ = 1;  // the neighbours are probed when a cell first reaches them
    }
    Region probe(const openvdb::Coord& origin) const { return Region::of(*acc_, origin); }
    const Region& neighbour(int j) {
        if (!(probed_ >> j & 1)) {
            region_[j] = probe(origin_.offsetBy(j >> 2 & 1 ? 8 : 0, j >> 1 & 1 ? 8 : 0, j & 1 ? 8 : 0));
            probed_ |= 1u << j;
        }
        return region_[j];
    }

    void fromLeaf(int n, Value (&v)[2][2][2]) const {  // n: LeafNode::coordToOffset of the cell's low corner
        const Region& r = region_[0];
        if (!r.data) {
            for (auto& plane : v)
                for (auto& row : plane) row[0] = row[1] = r.constant;
            return;
        }
        const Value* d = r.data;
        v[0][0][0] = d[n], v[0][0][1] = d[n + 1], v[0][1][0] = d[n + 8], v[0][1][1] = d[n + 9];
        v[1][0][0] = d[n + 64], v[1][0][1] = d[n + 65], v[1][1][0] = d[n + 72], v[1][1][1] = d[n + 73];
    }
    void fromBlock(int lx, int ly, int lz, Value (&v)[2][2][2]) {
        // Per axis: the low and high corner's region step (0 or 1) and offset in it.
        const int sx = lx == 7, sy = ly == 7, sz = lz == 7;
        const int ox[2] = {lx << 6, sx ? 0 : (lx + 1) << 6}, oy[2] = {ly << 3, sy ? 0 : (ly + 1) << 3},
                  oz[2] = {lz, sz ? 0 : lz + 1};
        const int jx[2] = {0, sx << 2}, jy[2] = {0, sy << 1}, jz[2] = {0, sz};
        for (int dx = 0; dx < 2; ++dx)
            for (int dy = 0; dy < 2; ++dy)
                for (int dz = 0; dz < 2; ++dz)
                    v[dx][dy][dz] = neighbour(jx[dx] | jy[dy] | jz[dz]).at(ox[dx] | oy[dy] | oz[dz]);
    }

    const Accessor* acc_;
    const openvdb::math::Transform* xf_;
    const DenseCopy<GridT>* dense_ = nullptr;
    openvdb::Coord origin_{INT_MAX, INT_MAX, INT_MAX};  // no leaf origin: those are multiples of 8
    Region region_[8];                                 // the leaf at origin_ + 8 (dx, dy, dz), j = dx<<2 | dy<<1 | dz
    unsigned probed_ = 0;
};

using LeafSampler = BasicLeafSampler<openvdb::FloatGrid>;
// A volume's emission (radiance per voxel length, RGB).
using Vec3LeafSampler = BasicLeafSampler<openvdb::Vec3SGrid>;

}  // namespace weft
