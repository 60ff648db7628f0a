#include "core/volume/screen_footprint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace weft {

namespace {

// In pixels: far above the projection's rounding (about 1e-12 of a pixel),
// far below a pixel, so the footprint stays tight.
constexpr double kPad = 1.0 / 64;

}  // namespace

ScreenFootprint::ScreenFootprint(const CameraRays& rays, int width, int height)
    : rays_(rays), width_(width), height_(height), marked_(std::size_t(width) * std::size_t(height), 0) {}

void ScreenFootprint::addIndexBox(const openvdb::math::Transform& xf, const Vec3d& lo, const Vec3d& hi) {
    if (all_) return;
    if (!xf.isLinear()) return markAll();  // a frustum bends the box's edges: its corners do not bound it
    double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = -x0, y1 = -x0;
    int behind = 0;
    for (int c = 0; c < 8; ++c) {
        const Vec3d corner(c & 1 ? hi.x() : lo.x(), c & 2 ? hi.y() : lo.y(), c & 4 ? hi.z() : lo.z());
        double px, py;
        if (!rays_.project(xf.indexToWorld(corner), px, py)) {
            ++behind;
            continue;
        }
        x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
    }
    if (behind == 8) return;  // wholly behind the eye: no ray of the image reaches it
    if (behind > 0) return markAll();  // the eye's plane cuts it: its image is unbounded
    markRect(x0 - kPad, y0 - kPad, x1 + kPad, y1 + kPad);
}

void ScreenFootprint::markRect(double x0, double y0, double x1, double y1) {
    if (!(x1 >= 0 && y1 >= 0 && x0 < width_ && y0 < height_)) return;  // off the image (or NaN)
    const int ix0 = int(std::max(0.0, std::floor(x0))), iy0 = int(std::max(0.0, std::floor(y0)));
    const int ix1 = int(std::min(width_ - 1.0, std::floor(x1))), iy1 = int(std::min(height_ - 1.0, std::floor(y1)));
    for (int y = iy0; y <= iy1; ++y)
        std::fill_n(marked_.begin() + std::ptrdiff_t(y) * width_ + ix0, ix1 - ix0 + 1, std::uint8_t(1));
}

double ScreenFootprint::coveredFraction() const {
    if (all_ || marked_.empty()) return 1.0;
    return double(std::count(marked_.begin(), marked_.end(), std::uint8_t(1))) / double(marked_.size());
}

}  // namespace weft
