#pragma once
// A pinhole camera in world space. Image coordinates are continuous pixels:
// (0,0) is the top-left corner of the top-left pixel, pixel centres at +0.5.
#include <openvdb/math/BBox.h>
#include <openvdb/math/Vec3.h>

#include <utility>
#include <vector>

namespace weft {

using Vec3d = openvdb::math::Vec3d;
using Vec3f = openvdb::math::Vec3s;
using BBoxd = openvdb::math::BBox<Vec3d>;

// Between the double vectors of the scene and OpenVDB and the float ones of
// Embree and shading.
inline Vec3f toVec3f(const Vec3d& v) { return Vec3f(float(v.x()), float(v.y()), float(v.z())); }
inline Vec3d toVec3d(const Vec3f& v) { return Vec3d(v.x(), v.y(), v.z()); }

struct Ray {
    Vec3d origin;
    Vec3d dir;  // unit length
};

struct Camera {
    Vec3d eye{0, 0, 5};
    Vec3d target{0, 0, 0};
    Vec3d up{0, 1, 0};
    double fovY = 40.0;  // vertical field of view, degrees

    Ray generate(double px, double py, int width, int height) const;

    // Looks down -z at the box centre from far enough that the whole box fits
    // the frame, with a small margin (how a bare .vdb or mesh is framed).
    static Camera framing(const BBoxd& box, double fovY, double aspect);
};

// A camera's rays for one image size with its frame (axes, tangent) built
// once: Camera::generate per pixel without the per-ray normalisations and
// tangent, the same rays bit for bit (generate is made of it).
class CameraRays {
public:
    CameraRays(const Camera& camera, int width, int height);
    Ray at(double px, double py) const {
        const double sx = (2.0 * px / width_ - 1.0) * tanHalf_ * aspect_;
        const double sy = (1.0 - 2.0 * py / height_) * tanHalf_;
        return {eye_, (forward_ + right_ * sx + up_ * sy).unitSafe()};
    }
    // The image point whose ray passes through p: at()'s inverse. False
    // where p is not in front of the eye (no ray of the image reaches it).
    bool project(const Vec3d& p, double& px, double& py) const;
    const Vec3d& eye() const { return eye_; }
    const Vec3d& forward() const { return forward_; }  // unit length

private:
    Vec3d eye_, forward_, right_, up_;
    double tanHalf_, aspect_, width_, height_;
};

// eye, target, up and field of view interpolated linearly (t in [0, 1]).
Camera lerpCamera(const Camera& a, const Camera& b, double t);

// A camera keyed by frame: linear between the keys around a (fractional)
// frame, held before the first key and after the last.
struct CameraPath {
    std::vector<std::pair<double, Camera>> keys;  // frames strictly increasing

    bool empty() const { return keys.empty(); }
    Camera at(double frame) const;
};

// When the shutter is open, in frames relative to the frame rendered:
// [-0.25, 0.25] is a 180-degree shutter centred on the frame, [0, 0] an
// instant (no motion blur). A camera sample's time u in [0, 1) is the frame
// time frame + open + u * (close - open).
struct Shutter {
    double open = 0, close = 0;
    bool instant() const { return open == close; }
    double frameTime(double frame, double u) const { return frame + open + u * (close - open); }
};

}  // namespace weft
