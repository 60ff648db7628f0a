#include "core/volume/volume_ray.hpp"

#include <algorithm>
#include <limits>
#include <tuple>

namespace weft {

std::optional<std::pair<double, double>> clipToBox(const Vec3d& origin, const Vec3d& dir, const openvdb::CoordBBox& box) {
    double t0 = 0, t1 = std::numeric_limits<double>::max();
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = box.min()[axis], hi = box.max()[axis];
        const double o = origin[axis], d = dir[axis];
        if (std::abs(d) < 1e-300) {
            if (o < lo || o > hi) return std::nullopt;
            continue;
        }
        double ta = (lo - o) / d, tb = (hi - o) / d;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
    if (!(t1 > t0)) return std::nullopt;
    return std::make_pair(t0, t1);
}

std::optional<IndexRay> toIndexRay(const Ray& worldRay, const Volume& volume) {
    if (volume.empty()) return std::nullopt;
    const auto& xf = volume.grid->transform();
    IndexRay ray;
    ray.origin = xf.worldToIndex(worldRay.origin);
    const Vec3d ahead = xf.worldToIndex(worldRay.origin + worldRay.dir);
    ray.speed = (ahead - ray.origin).length();
    ray.dir = (ahead - ray.origin).unitSafe();
    const auto span = clipToBox(ray.origin, ray.dir, volume.indexBox());
    if (!span) return std::nullopt;
    std::tie(ray.t0, ray.t1) = *span;
    return ray;
}

IndexDirections::IndexDirections(const Volume& volume) {
    const openvdb::math::MapBase& map = *volume.grid->transform().baseMap();
    for (int axis = 0; axis < 3; ++axis) {
        Vec3d unit(0.0);
        unit[axis] = 1;
        column_[axis] = map.applyInverseJacobian(unit);
    }
}

void mergeIntervals(std::vector<RayInterval>& intervals) {
    std::sort(intervals.begin(), intervals.end(), [](const RayInterval& a, const RayInterval& b) { return a.lo < b.lo; });
    std::size_t out = 0;
    for (std::size_t i = 0; i < intervals.size(); ++i) {
        if (out > 0 && intervals[i].lo <= intervals[out - 1].hi) intervals[out - 1].hi = std::max(intervals[out - 1].hi, intervals[i].hi);
        else intervals[out++] = intervals[i];
    }
    intervals.resize(out);
}

}  // namespace weft
