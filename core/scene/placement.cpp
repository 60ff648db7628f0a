#include "core/scene/placement.hpp"

#include <cmath>

namespace weft {

openvdb::math::Mat4d Placement::matrix() const {
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.postScale(scale);
    const double toRadians = M_PI / 180.0;
    m.postRotate(openvdb::math::X_AXIS, rotateDegrees.x() * toRadians);
    m.postRotate(openvdb::math::Y_AXIS, rotateDegrees.y() * toRadians);
    m.postRotate(openvdb::math::Z_AXIS, rotateDegrees.z() * toRadians);
    m.postTranslate(translate);
    return m;
}

}  // namespace weft
