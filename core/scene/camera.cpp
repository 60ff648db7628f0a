#include "core/scene/camera.hpp"

#include <algorithm>
#include <cmath>

namespace weft {

Ray Camera::generate(double px, double py, int width, int height) const { return CameraRays(*this, width, height).at(px, py); }

CameraRays::CameraRays(const Camera& c, int width, int height)
    : eye_(c.eye), forward_((c.target - c.eye).unitSafe()), right_(forward_.cross(c.up).unitSafe()), up_(right_.cross(forward_)),
      tanHalf_(std::tan(0.5 * c.fovY * M_PI / 180.0)), aspect_(double(width) / double(height)), width_(width), height_(height) {}

bool CameraRays::project(const Vec3d& p, double& px, double& py) const {
    const Vec3d d = p - eye_;
    const double depth = d.dot(forward_);
    if (!(depth > 0)) return false;
    px = (d.dot(right_) / (depth * tanHalf_ * aspect_) + 1.0) * 0.5 * width_;
    py = (1.0 - d.dot(up_) / (depth * tanHalf_)) * 0.5 * height_;
    return true;
}

Camera lerpCamera(const Camera& a, const Camera& b, double t) {
    Camera c;
    c.eye = a.eye + (b.eye - a.eye) * t;
    c.target = a.target + (b.target - a.target) * t;
    c.up = a.up + (b.up - a.up) * t;
    c.fovY = a.fovY + (b.fovY - a.fovY) * t;
    return c;
}

Camera CameraPath::at(double frame) const {
    if (keys.empty()) return Camera{};
    if (!(frame > keys.front().first)) return keys.front().second;  // NaN holds the first key too
    for (std::size_t i = 1; i < keys.size(); ++i)
        if (frame <= keys[i].first) {
            const double t = (frame - keys[i - 1].first) / (keys[i].first - keys[i - 1].first);
            return lerpCamera(keys[i - 1].second, keys[i].second, t);
        }
    return keys.back().second;
}

Camera Camera::framing(const BBoxd& given, double fovY, double aspect) {
    // Nothing to frame (an empty grid, the first frame of a cache): the unit cube.
    const bool some = given.min().x() <= given.max().x() && given.min().y() <= given.max().y() && given.min().z() <= given.max().z();
    const BBoxd box = some ? given : BBoxd(Vec3d(-0.5), Vec3d(0.5));
    const Vec3d center = box.getCenter();
    const Vec3d extent = box.extents() * 0.5;
    const double tanHalfY = std::tan(0.5 * fovY * M_PI / 180.0);
    const double tanHalfX = tanHalfY * aspect;
    // Distance at which the front face's half extents fit both fields of view.
    const double fitY = extent.y() / tanHalfY, fitX = extent.x() / tanHalfX;
    const double distance = extent.z() + 1.1 * std::max(fitX, fitY);
    Camera cam;
    cam.fovY = fovY;
    cam.target = center;
    cam.eye = center + Vec3d(0, 0, std::max(distance, 1e-6));
    return cam;
}

}  // namespace weft
