#pragma once
// A pinhole camera in world space. Image coordinates are continuous pixels:
// (0,0) is the top-left corner of the top-left pixel, pixel centres at +0.5.
#include <openvdb/math/BBox.h>
#include <openvdb/math/Vec3.h>

namespace weft {

using Vec3d = openvdb::math::Vec3d;
using Vec3f = openvdb::math::Vec3s;
using BBoxd = openvdb::math::BBox<Vec3d>;

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

}  // namespace weft
