#include "core/volume/skip/screen_footprint.hpp"

#include <algorithm>
#include <cmath>

namespace weft {

namespace {

// In pixels: far above the projection's rounding (about 1e-12 of a pixel),
// far below a pixel, so the footprint stays tight.
constexpr double kPad = 1.0 / 64;
constexpr float kInf = std::numeric_limits<float>::infinity();

float roundedDown(double x) {
    const float f = float(x);
    return double(f) > x ? std::nextafter(f, -kInf) : f;
}

float roundedUp(double x) {
    const float f = float(x);
    return double(f) < x ? std::nextafter(f, kInf) : f;
}

}  // namespace

ScreenFootprint::ScreenFootprint(const CameraRays& rays, int width, int height)
    : rays_(rays), width_(width), height_(height), tilesX_((width + kTile - 1) / kTile),
      marked_(std::size_t(width) * std::size_t(height), 0),
      near_(std::size_t(tilesX_) * std::size_t((height + kTile - 1) / kTile), kInf), far_(near_.size(), -kInf) {}

void ScreenFootprint::addIndexBox(const openvdb::math::Transform& xf, const Vec3d& lo, const Vec3d& hi) {
    if (all_) return;
    if (!xf.isLinear()) return markAll();  // a frustum bends the box's edges: its corners do not bound it
    double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = -x0, y1 = -x0, d0 = x0, d1 = -x0;
    int behind = 0;
    for (int c = 0; c < 8; ++c) {
        const Vec3d corner = xf.indexToWorld(Vec3d(c & 1 ? hi.x() : lo.x(), c & 2 ? hi.y() : lo.y(), c & 4 ? hi.z() : lo.z()));
        double px, py;
        if (!rays_.project(corner, px, py)) {
            ++behind;
            continue;
        }
        const double depth = (corner - rays_.eye()).dot(rays_.forward());
        x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
        d0 = std::min(d0, depth), d1 = std::max(d1, depth);
    }
    if (behind == 8) return;  // wholly behind the eye: no ray of the image reaches it
    if (behind > 0) return markAll();  // the eye's plane cuts it: its image is unbounded
    // Depth is linear, so the box's points lie between its corners' depths.
    markRect(x0 - kPad, y0 - kPad, x1 + kPad, y1 + kPad, roundedDown(d0), roundedUp(d1));
}

void ScreenFootprint::markRect(double x0, double y0, double x1, double y1, float nearDepth, float farDepth) {
    if (!(x1 >= 0 && y1 >= 0 && x0 < width_ && y0 < height_)) return;  // off the image (or NaN)
    const int ix0 = int(std::max(0.0, std::floor(x0))), iy0 = int(std::max(0.0, std::floor(y0)));
    const int ix1 = int(std::min(width_ - 1.0, std::floor(x1))), iy1 = int(std::min(height_ - 1.0, std::floor(y1)));
    for (int y = iy0; y <= iy1; ++y)
        std::fill_n(marked_.begin() + std::ptrdiff_t(y) * width_ + ix0, ix1 - ix0 + 1, std::uint8_t(1));
    for (int ty = iy0 / kTile; ty <= iy1 / kTile; ++ty)
        for (int tx = ix0 / kTile; tx <= ix1 / kTile; ++tx) {
            const std::size_t t = std::size_t(ty) * std::size_t(tilesX_) + std::size_t(tx);
            near_[t] = std::min(near_[t], nearDepth), far_[t] = std::max(far_[t], farDepth);
        }
}

// A point of the ray at t has depth t (dir . forward): a box between depths
// n and f holds points of the ray only for t in [n, f] / (dir . forward).
void ScreenFootprint::rayRange(double px, double py, const Vec3d& dir, double& t0, double& t1) const {
    t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
    if (all_ || !(px >= 0 && py >= 0 && px < width_ && py < height_)) return;
    const int x = int(px), y = int(py);
    if (!marked_[std::size_t(y) * std::size_t(width_) + std::size_t(x)]) return (void)(t0 = 1, t1 = 0);
    const std::size_t i = std::size_t(y / kTile) * std::size_t(tilesX_) + std::size_t(x / kTile);
    const double cosine = dir.dot(rays_.forward());  // > 0 for a ray of the image
    constexpr double kSlack = 1e-9;  // relative: covers the rounding of the depths and of the ray's own clips
    t0 = double(near_[i]) / cosine * (1 - kSlack), t1 = double(far_[i]) / cosine * (1 + kSlack);
}

double ScreenFootprint::coveredFraction() const {
    if (all_ || marked_.empty()) return 1.0;
    return double(std::count(marked_.begin(), marked_.end(), std::uint8_t(1))) / double(marked_.size());
}

}  // namespace weft
