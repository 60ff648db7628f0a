#pragma once
// The pixels of a still pinhole camera's image whose rays can reach a set
// of boxes, and how far along them: each box's corners projected, the
// pixels of the rectangle around them marked with the box's range of depths
// (along the camera's forward axis). A box wholly in front of the eye
// projects inside the hull of its corners' images, so a ray through an
// unmarked point misses every box, and a march whose samples can only add
// something inside them is skipped there: empty space skipped in the image
// plane, as a GPU volume renderer does by rasterising proxy boxes, instead
// of ray by ray. Where a ray does pass, the depths bound where along it a
// box can be (per tile of pixels), so its walk through the blocks starts and
// ends there.
#include <openvdb/math/Transform.h>

#include <cstdint>
#include <limits>
#include <vector>

#include "core/scene/camera.hpp"
#include "core/volume/skip/visible_blocks.hpp"

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

    // [t0, t1] of the ray through the continuous image point (px, py), with
    // unit direction dir (the camera's ray there), that holds every point of
    // a box it crosses; t0 > t1 where it crosses none. Unbounded outside the
    // image (a wide filter's samples), where nothing was marked.
    void rayRange(double px, double py, const Vec3d& dir, double& t0, double& t1) const;
    bool covers(double px, double py) const {
        double t0, t1;
        rayRange(px, py, rays_.forward(), t0, t1);
        return t0 <= t1;
    }
    double coveredFraction() const;

private:
    void markRect(double x0, double y0, double x1, double y1, float nearDepth, float farDepth);

    // Depths are kept per tile of kTile^2 pixels: a sixteenth of the
    // updates (the footprint of the aneurism scene at 512x512 took 6 ms
    // per pixel, under 1 ms so), the walk's bounds a little looser.
    static constexpr int kTile = 4;

    CameraRays rays_;
    int width_, height_, tilesX_;
    std::vector<std::uint8_t> marked_;  // per pixel, rows
    // Per tile, rows: the least and greatest depth of the boxes marked
    // there (rounded outwards); near > far where none is.
    std::vector<float> near_, far_;
    bool all_ = false;
};

}  // namespace weft
