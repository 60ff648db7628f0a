#include "core/volume/skip/visible_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#define WEFT_SSE2_ROWS 1
#endif

#include "core/volume/grid/leaf_sampler.hpp"  // floorToInt
#include "core/volume/grid/tiles_where.hpp"

namespace weft {

namespace {

int blockOf(int voxel) { return voxel >> 3; }  // floor(voxel / 8), negative voxels included

// A ray with its direction's reciprocals, taken once: the walk and the
// box clips below multiply instead of dividing.
struct WalkRay {
    Vec3d origin, dir, inv;
    explicit WalkRay(const IndexRay& r) : origin(r.origin), dir(r.dir) {
        for (int a = 0; a < 3; ++a) inv[a] = r.dir[a] != 0 ? 1.0 / r.dir[a] : 0.0;
    }
    Vec3d at(double t) const { return origin + dir * t; }
};

// [t0, t1] where origin + t dir lies in [lo, hi] on every axis; t0 > t1 where never.
void clipToBox(const WalkRay& ray, const Vec3d& lo, const Vec3d& hi, double& t0, double& t1) {
    for (int a = 0; a < 3; ++a) {
        const double o = ray.origin[a];
        if (ray.dir[a] == 0) {
            if (o < lo[a] || o > hi[a]) t0 = 1, t1 = 0;
            continue;
        }
        double ta = (lo[a] - o) * ray.inv[a], tb = (hi[a] - o) * ray.inv[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
}

}  // namespace

std::unique_ptr<VisibleBlocks> VisibleBlocks::of(const openvdb::FloatGrid& cells, std::size_t maxBlocks) {
    const openvdb::CoordBBox box = cells.evalActiveVoxelBoundingBox();
    if (box.empty()) return nullptr;
    auto blocks = std::make_unique<VisibleBlocks>();
    if (!blocks->allocate(box, maxBlocks)) return nullptr;
    blocks->masks_.assign(blocks->boxes_.size(), nullptr);
    static const openvdb::util::NodeMask<3> allOn(true);
    for (auto leaf = cells.tree().cbeginLeaf(); leaf; ++leaf) {
        openvdb::CoordBBox on;  // empty; the leaf adds its active voxels' box (visitVoxels: tight, not the node's)
        leaf->evalActiveBoundingBox(on, true);
        if (on.empty()) continue;
        const openvdb::Coord lo = on.min() - leaf->origin(), hi = on.max() - leaf->origin();
        blocks->blockAt(leaf->origin()).add(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z());
        blocks->masks_[blocks->blockIndex(leaf->origin())] = &leaf->getValueMask();
    }
    auto tiles = cells.tree().cbeginValueOn();  // active tiles: whole blocks visible
    tiles.setMaxDepth(openvdb::FloatTree::ValueOnCIter::LEAF_DEPTH - 1);
    for (; tiles; ++tiles) {
        openvdb::CoordBBox tile;
        tiles.getBoundingBox(tile);
        for (int x = tile.min().x(); x <= tile.max().x(); x += 8)
            for (int y = tile.min().y(); y <= tile.max().y(); y += 8)
                for (int z = tile.min().z(); z <= tile.max().z(); z += 8) {
                    blocks->blockAt(openvdb::Coord(x, y, z)).add(0, 0, 0, 7, 7, 7);
                    blocks->masks_[blocks->blockIndex(openvdb::Coord(x, y, z))] = &allOn;
                }
    }
    blocks->measureClearance();
    return blocks;
}

void VisibleBlocks::Box::add(int l0, int l1, int l2, int h0, int h1, int h2) {
    const int l[3] = {l0, l1, l2}, h[3] = {h0, h1, h2};
    for (int a = 0; a < 3; ++a) {
        lo[a] = std::uint8_t(std::min<int>(lo[a], l[a]));
        hi[a] = std::uint8_t(std::max<int>(hi[a], h[a]));
    }
}

bool VisibleBlocks::allocate(const openvdb::CoordBBox& box, std::size_t maxBlocks) {
    origin_ = openvdb::Coord(box.min().x() & ~7, box.min().y() & ~7, box.min().z() & ~7);
    double count = 1;
    for (int a = 0; a < 3; ++a) {
        dims_[a] = blockOf(box.max()[a]) - blockOf(box.min()[a]) + 1;
        count *= dims_[a];
    }
    if (count > double(maxBlocks)) return false;
    boxes_.resize(std::size_t(count));
    return true;
}

std::size_t VisibleBlocks::blockIndex(const openvdb::Coord& voxel) const {
    const openvdb::Coord b = voxel - origin_;
    return indexOf(blockOf(b.x()), blockOf(b.y()), blockOf(b.z()));
}

VisibleBlocks::Box& VisibleBlocks::blockAt(const openvdb::Coord& voxel) { return boxes_[blockIndex(voxel)]; }

namespace {

// Per axis, the bits of the local coordinates (0..7) where a leaf holds a
// value at or above the cutoff; zero where none does. Their lowest and
// highest bits bound those voxels (a set's box is its projections' box).
struct AxisBits {
    unsigned bits[3] = {0, 0, 0};
    bool none() const { return bits[0] == 0; }
    int lo(int a) const { return __builtin_ctz(bits[a]); }
    int hi(int a) const { return 31 - __builtin_clz(bits[a]); }
};

// The z's of one row of eight voxels (x, y fixed) at or above the cutoff, as bits.
inline unsigned reachingRow(const float* v, float cutoff) {
#if WEFT_SSE2_ROWS
    const __m128 c = _mm_set1_ps(cutoff);  // >= is false for NaN, as in the scalar test
    return unsigned(_mm_movemask_ps(_mm_cmpge_ps(_mm_loadu_ps(v), c))) |
           unsigned(_mm_movemask_ps(_mm_cmpge_ps(_mm_loadu_ps(v + 4), c))) << 4;
#else
    unsigned row = 0;
    for (int z = 0; z < 8; ++z) row |= unsigned(v[z] >= cutoff) << z;
    return row;
#endif
}

// A row at a time, without a branch per voxel: the test is as good as
// random to the predictor at a feature's edge, and every leaf is read.
AxisBits reachingBits(const openvdb::FloatTree::LeafNodeType& leaf, float cutoff) {
    AxisBits out;
    const float* v = leaf.buffer().data();
    for (unsigned x = 0; x < 8; ++x)
        for (unsigned y = 0; y < 8; ++y) {
            const unsigned row = reachingRow(v + 8 * (8 * x + y), cutoff), any = row != 0;
            out.bits[0] |= any << x, out.bits[1] |= any << y, out.bits[2] |= row;
        }
    return out;
}

}  // namespace

std::unique_ptr<VisibleBlocks> VisibleBlocks::reaching(const openvdb::FloatGrid& grid, float cutoff, Within within,
                                                       std::size_t maxBlocks) {
    if (!(grid.background() < cutoff)) return nullptr;
    using Leaf = openvdb::FloatTree::LeafNodeType;
    std::vector<const Leaf*> leaves;
    leaves.reserve(grid.tree().leafCount());
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) leaves.push_back(leaf.getLeaf());
    std::vector<AxisBits> bits(leaves.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 64), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) bits[i] = reachingBits(*leaves[i], cutoff);
    });
    // Cells [c, c + 1) reach the cutoff for c in [voxel - 1, voxel] on each
    // axis: a leaf's reaching voxels [lo, hi] make the cells [lo - 1, hi],
    // and a tile's [min - 1, max].
    const std::vector<openvdb::CoordBBox> tiles =
        tilesWhere(grid.tree(), within == Within::ActiveBlocks, [cutoff](float v) { return v >= cutoff; });
    openvdb::CoordBBox box;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        if (bits[i].none()) continue;
        const openvdb::Coord o = leaves[i]->origin();
        box.expand(openvdb::CoordBBox(o.offsetBy(bits[i].lo(0) - 1, bits[i].lo(1) - 1, bits[i].lo(2) - 1),
                                      o.offsetBy(bits[i].hi(0), bits[i].hi(1), bits[i].hi(2))));
    }
    for (const openvdb::CoordBBox& t : tiles) box.expand(openvdb::CoordBBox(t.min().offsetBy(-1), t.max()));
    auto blocks = std::make_unique<VisibleBlocks>();
    if (box.empty()) return blocks;  // nothing reaches: no blocks, every ray's intervals are empty
    if (!blocks->allocate(box, maxBlocks)) return nullptr;
    const openvdb::FloatGrid::ConstAccessor acc = grid.getConstAccessor();
    const auto active = [&](const openvdb::Coord& origin) {  // a block the march reads
        if (within == Within::Anywhere) return true;
        if (const auto* leaf = acc.probeConstLeaf(origin)) return !leaf->isEmpty();
        return acc.isValueOn(origin);
    };
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        if (bits[i].none()) continue;
        const AxisBits& b = bits[i];
        const openvdb::Coord o = leaves[i]->origin();
        // Per axis the cells in this block, [max(lo - 1, 0), hi], and, when
        // lo is 0, the one cell (7) of the block below along it.
        for (int j = 0; j < 8; ++j) {  // j = bx << 2 | by << 1 | bz: 1 on an axis is the block below
            const int below[3] = {j >> 2 & 1, j >> 1 & 1, j & 1};
            int l[3], h[3];
            bool inside = true;
            for (int a = 0; a < 3; ++a) {
                if (below[a]) inside = inside && b.lo(a) == 0, l[a] = h[a] = 7;
                else l[a] = std::max(b.lo(a) - 1, 0), h[a] = b.hi(a);
            }
            const openvdb::Coord at = o.offsetBy(-8 * below[0], -8 * below[1], -8 * below[2]);
            if (inside && active(at)) blocks->blockAt(at).add(l[0], l[1], l[2], h[0], h[1], h[2]);
        }
    }
    for (const openvdb::CoordBBox& t : tiles)
        for (int x = t.min().x() - 8; x <= t.max().x(); x += 8)
            for (int y = t.min().y() - 8; y <= t.max().y(); y += 8)
                for (int z = t.min().z() - 8; z <= t.max().z(); z += 8)
                    if (active(openvdb::Coord(x, y, z))) blocks->blockAt(openvdb::Coord(x, y, z)).add(0, 0, 0, 7, 7, 7);
    blocks->measureClearance();
    return blocks;
}

std::size_t VisibleBlocks::visibleBlockCount() const {
    return std::size_t(std::count_if(boxes_.begin(), boxes_.end(), [](const Box& b) { return !b.empty(); }));
}

// Chessboard distance in blocks to the nearest visible block: a two-pass
// chamfer over the 26 neighbours, exact for this metric.
void VisibleBlocks::measureClearance() {
    constexpr int kFar = 255;
    clearance_.assign(boxes_.size(), kFar);
    for (std::size_t i = 0; i < boxes_.size(); ++i)
        if (!boxes_[i].empty()) clearance_[i] = 0;
    const auto pass = [&](int from, int sign) {  // sign +1: raster order, the 13 neighbours before; -1: after
        for (int i = from == 0 ? 0 : dims_[0] - 1; i >= 0 && i < dims_[0]; i += sign)
            for (int j = from == 0 ? 0 : dims_[1] - 1; j >= 0 && j < dims_[1]; j += sign)
                for (int k = from == 0 ? 0 : dims_[2] - 1; k >= 0 && k < dims_[2]; k += sign) {
                    int best = clearance_[indexOf(i, j, k)];
                    for (int di = -1; di <= 1; ++di)
                        for (int dj = -1; dj <= 1; ++dj)
                            for (int dk = -1; dk <= 1; ++dk) {
                                const int order = (di * 3 + dj) * 3 + dk;  // neighbours earlier in the pass's order
                                if (order * sign >= 0) continue;
                                const int ni = i + di, nj = j + dj, nk = k + dk;
                                if (ni < 0 || nj < 0 || nk < 0 || ni >= dims_[0] || nj >= dims_[1] || nk >= dims_[2]) continue;
                                best = std::min(best, clearance_[indexOf(ni, nj, nk)] + 1);
                            }
                    clearance_[indexOf(i, j, k)] = std::uint8_t(best);
                }
    };
    pass(0, 1);
    pass(1, -1);
}

void VisibleBlocks::intervals(const IndexRay& indexRay, double perU, std::vector<RayInterval>& out) const {
    if (boxes_.empty()) return;  // nothing visible
    const WalkRay ray(indexRay);
    const Vec3d lo = origin_.asVec3d();
    double tIn = indexRay.t0, tOut = indexRay.t1;
    clipToBox(ray, lo, lo + Vec3d(dims_[0], dims_[1], dims_[2]) * 8.0, tIn, tOut);
    if (!(tIn <= tOut)) return;
    const std::size_t first = out.size();
    const auto visitBlock = [&](int bx, int by, int bz, const Box& box) {
        const auto [boxLo, boxHi] = boundsOf(bx, by, bz, box);
        double t0 = tIn, t1 = tOut;
        clipToBox(ray, boxLo, boxHi, t0, t1);
        if (!(t0 <= t1)) return;
        const RayInterval in{t0 / perU, t1 / perU};
        if (out.size() > first && in.lo <= out.back().hi)
            out.back().lo = std::min(out.back().lo, in.lo), out.back().hi = std::max(out.back().hi, in.hi);
        else
            out.push_back(in);
    };
    // Per axis: the step in block coordinates and in the flat array, the
    // parameter between two faces, and how far the array reaches.
    const std::ptrdiff_t stride[3] = {std::ptrdiff_t(dims_[1]) * dims_[2], dims_[2], 1};
    int step[3];
    std::ptrdiff_t flatStep[3];
    double tDelta[3];
    for (int a = 0; a < 3; ++a) {
        const double d = ray.dir[a];
        step[a] = d > 0 ? 1 : d < 0 ? -1 : 0;
        flatStep[a] = step[a] * stride[a];
        tDelta[a] = d != 0 ? 8.0 * std::abs(ray.inv[a]) : std::numeric_limits<double>::infinity();
    }
    // Amanatides & Woo from block to block, stepping the axis whose face
    // comes first; scalars, not arrays, so the loop stays in registers.
    // From a block whose clearance is c >= 3, the ray jumps (c - 1) * 8
    // voxels ahead: every point within that (chessboard) distance lies in
    // a block nearer than c, so none it passes is visible.
    double t = tIn;
    while (t <= tOut) {
        const Vec3d start = ray.at(t) - lo;
        int idx[3];
        double tNext[3];
        for (int a = 0; a < 3; ++a) {
            idx[a] = std::clamp(floorToInt(start[a] * 0.125), 0, dims_[a] - 1);
            tNext[a] = step[a] != 0 ? (lo[a] + 8.0 * (idx[a] + (step[a] > 0)) - ray.origin[a]) * ray.inv[a]
                                    : std::numeric_limits<double>::infinity();
        }
        int bx = idx[0], by = idx[1], bz = idx[2];
        double tx = tNext[0], ty = tNext[1], tz = tNext[2];
        std::ptrdiff_t i = std::ptrdiff_t(indexOf(bx, by, bz));
        double tEnter = t;
        t = std::numeric_limits<double>::infinity();  // no jump: the walk below ends the ray
        for (;;) {
            const int clear = clearance_[std::size_t(i)];
            if (clear >= 3) {
                t = tEnter + (clear - 1) * 8.0;
                break;
            }
            if (clear == 0) visitBlock(bx, by, bz, boxes_[std::size_t(i)]);
            if (tx < ty && tx < tz) {
                bx += step[0];
                if (tx > tOut || unsigned(bx) >= unsigned(dims_[0])) break;
                i += flatStep[0], tEnter = tx, tx += tDelta[0];
            } else if (ty < tz) {
                by += step[1];
                if (ty > tOut || unsigned(by) >= unsigned(dims_[1])) break;
                i += flatStep[1], tEnter = ty, ty += tDelta[1];
            } else {
                bz += step[2];
                if (tz > tOut || unsigned(bz) >= unsigned(dims_[2])) break;
                i += flatStep[2], tEnter = tz, tz += tDelta[2];
            }
        }
    }
}

}  // namespace weft
