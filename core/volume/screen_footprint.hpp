#pragma once
// The pixels of a still pinhole camera's image whose rays can reach a set
// of boxes: each box's corners projected, the pixels of the rectangle
// around them marked. A box wholly in front of the eye projects inside the
// hull of its corners' images, so a ray through an unmarked point misses
// every box, and a march whose samples can only add something inside them
// is skipped there: empty space skipped in the image plane, as a GPU volume
// renderer does by rasterising proxy boxes, instead of ray by ray.
#include <openvdb/math/Transform.h>

#include <cstdint>
#include <vector>

#include "core/scene/camera.hpp"
#include "core/volume/visible_blocks.hpp"

namespace weft {

class ScreenFootprint {
public:
    ScreenFootprint(const CameraRays& rays, int width, int height);

    // Marks the pixels whose rays may cross the index-space box [lo, hi] of
    // a grid with transform `xf`; every pixel where the map is not affine
    // (a frustum) or the box reaches behind the eye.
    void addIndexBox(const openvdb::math::Transform& xf, const Vec3d& lo, const Vec3d& hi);
    // Every visible box of `blocks`, a grid's with transform `xf`.
    void addBlocks(const VisibleBlocks& blocks, const openvdb::math::Transform& xf) {
        blocks.forEachBox([&](const Vec3d& lo, const Vec3d& hi) { addIndexBox(xf, lo, hi); });
    }
    void markAll() { all_ = true; }

    // Whether the ray through the continuous image point (px, py) may cross
    // a box; true outside the image (a wide filter's samples), where
    // nothing was marked.
    bool covers(double px, double py) const {
        if (all_) return true;
        if (!(px >= 0 && py >= 0 && px < width_ && py < height_)) return true;
        return marked_[std::size_t(int(py)) * std::size_t(width_) + std::size_t(int(px))] != 0;
    }
    double coveredFraction() const;

private:
    void markRect(double x0, double y0, double x1, double y1);

    CameraRays rays_;
    int width_, height_;
    std::vector<std::uint8_t> marked_;  // per pixel, rows
    bool all_ = false;
};

}  // namespace weft
