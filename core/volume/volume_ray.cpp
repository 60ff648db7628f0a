#include "core/volume/volume_ray.hpp"

#include <algorithm>
#include <limits>

namespace weft {

std::optional<IndexRay> toIndexRay(const Ray& worldRay, const Volume& volume) {
    if (volume.empty()) return std::nullopt;
    const auto& xf = volume.grid->transform();
    IndexRay ray;
    ray.origin = xf.worldToIndex(worldRay.origin);
    const Vec3d ahead = xf.worldToIndex(worldRay.origin + worldRay.dir);
    ray.speed = (ahead - ray.origin).length();
    ray.dir = (ahead - ray.origin).unitSafe();
    const openvdb::CoordBBox box = volume.indexBox();
    double t0 = 0, t1 = std::numeric_limits<double>::max();
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = box.min()[axis], hi = box.max()[axis];
        const double o = ray.origin[axis], d = ray.dir[axis];
        if (std::abs(d) < 1e-300) {
            if (o < lo || o > hi) return std::nullopt;
            continue;
        }
        double ta = (lo - o) / d, tb = (hi - o) / d;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
    if (!(t1 > t0)) return std::nullopt;
    ray.t0 = t0, ray.t1 = t1;
    return ray;
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
