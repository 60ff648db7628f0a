#include "core/volume/volume_motion.hpp"

#include <algorithm>

namespace weft {

namespace {

// Beyond this many bricks a pass would touch more bricks than a bound over
// the whole volume loses: every brick takes the largest bound instead.
constexpr int kMaxBrickRadius = 32;

openvdb::FloatGrid::Ptr dilatedAlong(const openvdb::FloatGrid& in, int axis, int radius) {
    auto out = openvdb::FloatGrid::create(in.background());
    auto acc = out->getAccessor();
    for (auto it = in.cbeginValueOn(); it; ++it) {
        openvdb::Coord c = it.getCoord();
        const int centre = c[axis];
        for (int d = -radius; d <= radius; ++d) {
            c[axis] = centre + d;
            if (*it > acc.getValue(c)) acc.setValue(c, *it);
        }
    }
    return out;
}

}  // namespace

openvdb::FloatGrid::Ptr dilatedBrickBounds(openvdb::FloatGrid::Ptr bricks, int radius) {
    if (radius <= 0) return bricks;
    if (radius > kMaxBrickRadius) {
        float largest = bricks->background();
        for (auto it = bricks->cbeginValueOn(); it; ++it) largest = std::max(largest, *it);
        return openvdb::FloatGrid::create(largest);
    }
    openvdb::FloatGrid::Ptr out = dilatedAlong(*bricks, 0, radius);
    out = dilatedAlong(*out, 1, radius);
    return dilatedAlong(*out, 2, radius);
}

}  // namespace weft
