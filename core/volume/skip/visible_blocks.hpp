#pragma once
// visibleCells' leaves as a dense array of 8^3 blocks over their bounding
// box, each holding the box of its visible cells. A ray walks the blocks in
// order (Amanatides & Woo's grid traversal, leaping over empty space by
// each block's distance to the nearest visible one: proximity clouds,
// Cohen & Sheffer 1994) and is marched only where it
// crosses a block's visible box: array reads instead of a descent of
// OpenVDB's tree (its HDDA), and a ray through a leaf that shows a thin
// vessel marches the few cells around it, not all eight voxels.
#include <openvdb/openvdb.h>

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/volume/grid/leaf_sampler.hpp"  // floorToInt
#include "core/volume/volume_ray.hpp"

namespace weft {

class VisibleBlocks {
public:
    // Boxes are widened by this many voxels, so a sample that rounding puts
    // on a box's face is still marched (the cell test then decides).
    static constexpr double kMargin = 1e-3;

    // Null where `cells` (visibleCells' grid) has no visible cell, or the
    // array would hold more than maxBlocks blocks (a sparse grid spread wide:
    // the HDDA serves it).
    static std::unique_ptr<VisibleBlocks> of(const openvdb::FloatGrid& cells, std::size_t maxBlocks = std::size_t(1) << 22);

    // The blocks straight from a density grid's values for a march that
    // counts densities below `cutoff` as empty: a lookup interpolates its
    // cell's eight corners, so it reaches the cutoff only in a cell with a
    // corner at or above it; each block's box holds those cells (the cells
    // just below such a voxel, on the block's low faces, spill into the
    // blocks below). Null as of() is, and where the background reaches the
    // cutoff (nothing can be skipped); an empty array where nothing reaches it.
    // Within::ActiveBlocks keeps only the blocks of leaves with active voxels
    // and of active tiles: a march that reads only those (OpenVDB's
    // intersector's leaves) then takes exactly the samples it would have
    // and can add something.
    enum class Within { Anywhere, ActiveBlocks };
    static std::unique_ptr<VisibleBlocks> reaching(const openvdb::FloatGrid& grid, float cutoff, Within within = Within::Anywhere,
                                                   std::size_t maxBlocks = std::size_t(1) << 22);

    // Appends the stretches of `ray` (within [ray.t0, ray.t1]) that cross a
    // visible box, in order, overlapping ones joined, each divided by
    // `perU` (index units per march unit).
    void intervals(const IndexRay& ray, double perU, std::vector<RayInterval>& out) const;

    // fn(lo, hi) for each block's visible box in index space, as
    // intervals() clips rays against it (the margin included).
    template <class Fn>
    void forEachBox(Fn&& fn) const;

    // Whether the cell holding index point p is visible: of()'s cells grid
    // active there (its leaf's mask bit, or an active tile). An array read
    // and a bit, not a descent of the tree; false outside the blocks. Only
    // blocks made by of() know their cells (reaching() keeps none).
    bool cellVisible(const Vec3d& p) const {
        const unsigned x = unsigned(floorToInt(p.x()) - origin_.x()), y = unsigned(floorToInt(p.y()) - origin_.y()),
                       z = unsigned(floorToInt(p.z()) - origin_.z());
        if (x >> 3 >= unsigned(dims_[0]) || y >> 3 >= unsigned(dims_[1]) || z >> 3 >= unsigned(dims_[2])) return false;
        const openvdb::util::NodeMask<3>* mask = masks_[indexOf(int(x >> 3), int(y >> 3), int(z >> 3))];
        return mask && mask->isOn((x & 7) << 6 | (y & 7) << 3 | (z & 7));
    }

    std::size_t blockCount() const { return boxes_.size(); }
    std::size_t visibleBlockCount() const;

private:
    struct Box {  // voxel offsets in the block; lo > hi: no visible cell
        std::uint8_t lo[3] = {255, 255, 255}, hi[3] = {0, 0, 0};
        bool empty() const { return lo[0] > hi[0]; }
        void add(int l0, int l1, int l2, int h0, int h1, int h2);  // joins the box [l, h] (offsets 0..7)
    };
    // Block (x, y, z)'s box in index space, widened by kMargin. A sample in
    // cell c lies in [c, c + 1): the far faces are hi + 1.
    std::pair<Vec3d, Vec3d> boundsOf(int x, int y, int z, const Box& b) const {
        const Vec3d corner = origin_.asVec3d() + Vec3d(x, y, z) * 8.0;
        return {corner + Vec3d(b.lo[0], b.lo[1], b.lo[2]) - Vec3d(kMargin),
                corner + Vec3d(b.hi[0] + 1.0, b.hi[1] + 1.0, b.hi[2] + 1.0) + Vec3d(kMargin)};
    }
    bool allocate(const openvdb::CoordBBox& box, std::size_t maxBlocks);  // false: too many blocks
    std::size_t blockIndex(const openvdb::Coord& voxel) const;
    Box& blockAt(const openvdb::Coord& voxel);
    void measureClearance();
    std::size_t indexOf(int i, int j, int k) const { return (std::size_t(i) * dims_[1] + j) * dims_[2] + k; }

    openvdb::Coord origin_;  // low corner of block (0, 0, 0), a multiple of 8
    int dims_[3] = {0, 0, 0};
    std::vector<Box> boxes_;
    std::vector<std::uint8_t> clearance_;  // chessboard distance in blocks to a visible block, at most 255
    // of()'s, per block: its cells' leaf mask, one all on for a tile; null where none.
    std::vector<const openvdb::util::NodeMask<3>*> masks_;
};

template <class Fn>
void VisibleBlocks::forEachBox(Fn&& fn) const {
    std::size_t i = 0;
    for (int x = 0; x < dims_[0]; ++x)
        for (int y = 0; y < dims_[1]; ++y)
            for (int z = 0; z < dims_[2]; ++z, ++i) {
                const Box& b = boxes_[i];
                if (b.empty()) continue;
                const auto [lo, hi] = boundsOf(x, y, z, b);
                fn(lo, hi);
            }
}

}  // namespace weft
