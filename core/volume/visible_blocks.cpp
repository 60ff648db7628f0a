#include "core/volume/visible_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

// Visits the cells (edge `size`, cell 0's low corner at lo) with indices in
// [first, last] that `ray` crosses within [tIn, tOut], in order, as
// visit(index, tEnter, tExit): Amanatides & Woo, stepping the axis whose
// face comes first.
template <class Visit>
void walkCells(const WalkRay& ray, const Vec3d& lo, double size, const int (&first)[3], const int (&last)[3], double tIn,
               double tOut, Visit&& visit) {
    const Vec3d start = ray.at(tIn) - lo;
    int idx[3], step[3];
    double tNext[3], tDelta[3];
    for (int a = 0; a < 3; ++a) {
        idx[a] = std::clamp(int(std::floor(start[a] / size)), first[a], last[a]);
        const double d = ray.dir[a];
        step[a] = d > 0 ? 1 : d < 0 ? -1 : 0;
        const double face = lo[a] + size * (idx[a] + (d > 0));
        tNext[a] = d != 0 ? (face - ray.origin[a]) * ray.inv[a] : std::numeric_limits<double>::infinity();
        tDelta[a] = d != 0 ? size * std::abs(ray.inv[a]) : std::numeric_limits<double>::infinity();
    }
    double tEnter = tIn;
    for (;;) {
        const int a = tNext[0] < tNext[1] ? (tNext[0] < tNext[2] ? 0 : 2) : (tNext[1] < tNext[2] ? 1 : 2);
        const double tExit = std::min(tNext[a], tOut);
        visit(idx, tEnter, tExit);
        if (tNext[a] > tOut) return;
        idx[a] += step[a];
        if (idx[a] < first[a] || idx[a] > last[a]) return;
        tEnter = tNext[a];
        tNext[a] += tDelta[a];
    }
}

}  // namespace

std::unique_ptr<VisibleBlocks> VisibleBlocks::of(const openvdb::FloatGrid& cells, std::size_t maxBlocks) {
    const openvdb::CoordBBox box = cells.evalActiveVoxelBoundingBox();
    if (box.empty()) return nullptr;
    auto blocks = std::make_unique<VisibleBlocks>();
    blocks->origin_ = openvdb::Coord(box.min().x() & ~7, box.min().y() & ~7, box.min().z() & ~7);
    double count = 1;
    for (int a = 0; a < 3; ++a) {
        blocks->dims_[a] = blockOf(box.max()[a]) - blockOf(box.min()[a]) + 1;
        count *= blocks->dims_[a];
    }
    if (count > double(maxBlocks)) return nullptr;
    blocks->boxes_.resize(std::size_t(count));
    const auto blockAt = [&](const openvdb::Coord& voxel) -> Box& {
        const openvdb::Coord b = voxel - blocks->origin_;
        return blocks->boxes_[blocks->indexOf(blockOf(b.x()), blockOf(b.y()), blockOf(b.z()))];
    };
    for (auto leaf = cells.tree().cbeginLeaf(); leaf; ++leaf) {
        openvdb::CoordBBox on;  // empty; the leaf adds its active voxels' box (visitVoxels: tight, not the node's)
        leaf->evalActiveBoundingBox(on, true);
        if (!on.empty()) {
            Box& b = blockAt(leaf->origin());
            for (int a = 0; a < 3; ++a) {
                b.lo[a] = std::uint8_t(on.min()[a] - leaf->origin()[a]);
                b.hi[a] = std::uint8_t(on.max()[a] - leaf->origin()[a]);
            }
        }
    }
    auto tiles = cells.tree().cbeginValueOn();  // active tiles: whole blocks visible
    tiles.setMaxDepth(openvdb::FloatTree::ValueOnCIter::LEAF_DEPTH - 1);
    for (; tiles; ++tiles) {
        openvdb::CoordBBox tile;
        tiles.getBoundingBox(tile);
        for (int x = tile.min().x(); x <= tile.max().x(); x += 8)
            for (int y = tile.min().y(); y <= tile.max().y(); y += 8)
                for (int z = tile.min().z(); z <= tile.max().z(); z += 8) {
                    Box& b = blockAt(openvdb::Coord(x, y, z));
                    for (int a = 0; a < 3; ++a) b.lo[a] = 0, b.hi[a] = 7;
                }
    }
    for (int a = 0; a < 3; ++a) blocks->groups_[a] = (blocks->dims_[a] + kGroup - 1) / kGroup;
    blocks->groupVisible_.assign(std::size_t(blocks->groups_[0]) * blocks->groups_[1] * blocks->groups_[2], 0);
    for (int i = 0; i < blocks->dims_[0]; ++i)
        for (int j = 0; j < blocks->dims_[1]; ++j)
            for (int k = 0; k < blocks->dims_[2]; ++k)
                if (!blocks->boxes_[blocks->indexOf(i, j, k)].empty())
                    blocks->groupVisible_[(std::size_t(i / kGroup) * blocks->groups_[1] + j / kGroup) * blocks->groups_[2] + k / kGroup] = 1;
    return blocks;
}

std::size_t VisibleBlocks::visibleBlockCount() const {
    return std::size_t(std::count_if(boxes_.begin(), boxes_.end(), [](const Box& b) { return !b.empty(); }));
}

void VisibleBlocks::intervals(const IndexRay& indexRay, double perU, std::vector<RayInterval>& out) const {
    const WalkRay ray(indexRay);
    const Vec3d lo = origin_.asVec3d();
    double tIn = indexRay.t0, tOut = indexRay.t1;
    clipToBox(ray, lo, lo + Vec3d(dims_[0], dims_[1], dims_[2]) * 8.0, tIn, tOut);
    if (!(tIn <= tOut)) return;
    const std::size_t first = out.size();
    const auto visitBlock = [&](const int (&b)[3], double, double) {
        const Box& box = boxes_[indexOf(b[0], b[1], b[2])];
        if (box.empty()) return;
        const Vec3d corner = lo + Vec3d(b[0], b[1], b[2]) * 8.0;
        double t0 = tIn, t1 = tOut;  // a sample in cell c lies in [c, c + 1): the box's far faces are hi + 1
        clipToBox(ray, corner + Vec3d(box.lo[0], box.lo[1], box.lo[2]) - Vec3d(kMargin),
                  corner + Vec3d(box.hi[0] + 1.0, box.hi[1] + 1.0, box.hi[2] + 1.0) + Vec3d(kMargin), t0, t1);
        if (!(t0 <= t1)) return;
        const RayInterval in{t0 / perU, t1 / perU};
        if (out.size() > first && in.lo <= out.back().hi)
            out.back().lo = std::min(out.back().lo, in.lo), out.back().hi = std::max(out.back().hi, in.hi);
        else
            out.push_back(in);
    };
    // Groups of kGroup^3 blocks with nothing visible are crossed in one step.
    const int none[3] = {0, 0, 0}, lastGroup[3] = {groups_[0] - 1, groups_[1] - 1, groups_[2] - 1};
    walkCells(ray, lo, 8.0 * kGroup, none, lastGroup, tIn, tOut, [&](const int (&g)[3], double t0, double t1) {
        if (!groupVisible_[(std::size_t(g[0]) * groups_[1] + g[1]) * groups_[2] + g[2]]) return;
        int from[3], to[3];
        for (int a = 0; a < 3; ++a) from[a] = g[a] * kGroup, to[a] = std::min(from[a] + kGroup, dims_[a]) - 1;
        walkCells(ray, lo, 8.0, from, to, t0, t1, visitBlock);
    });
}

}  // namespace weft
