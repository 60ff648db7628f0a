#pragma once
// Where a scene file puts an object: "scale" (a number or [sx, sy, sz]),
// "rotate" ([rx, ry, rz] in degrees, applied about x, then y, then z) and
// "translate", applied in that order to the object's own coordinates. Meshes
// and volumes read the same keys, so both move alike.
#include <openvdb/math/Mat4.h>

#include "core/scene/camera.hpp"

namespace weft {

struct Placement {
    Vec3d scale{1, 1, 1};
    Vec3d rotateDegrees{0, 0, 0};
    Vec3d translate{0, 0, 0};

    bool identity() const { return scale == Vec3d(1, 1, 1) && rotateDegrees == Vec3d(0, 0, 0) && translate == Vec3d(0, 0, 0); }
    // The affine map object -> world, for OpenVDB's row-vector convention
    // (p' = p * M: transform(p) applies scale, then rotations, then translation).
    openvdb::math::Mat4d matrix() const;
};

}  // namespace weft
