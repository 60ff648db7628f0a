#include "core/volume/slices.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/volume/volume_ray.hpp"

namespace weft {

SliceSetup makeSliceSetup(const Camera& camera, const Volume& volume, double spacing, int lmax) {
    SliceSetup s;
    s.eye = volume.grid->transform().worldToIndex(camera.eye);
    s.spacing = spacing;
    const openvdb::CoordBBox box = volume.indexBox();
    // Nearest and farthest points of the box from the eye.
    double nearSq = 0, farSq = 0;
    for (int a = 0; a < 3; ++a) {
        const double lo = box.min()[a], hi = box.max()[a], e = s.eye[a];
        const double dn = e < lo ? lo - e : e > hi ? e - hi : 0.0;
        const double df = std::max(std::abs(e - lo), std::abs(e - hi));
        nearSq += dn * dn, farSq += df * df;
    }
    s.tNear = std::sqrt(nearSq);
    const double count = std::ceil((std::sqrt(farSq) - s.tNear) / spacing);
    const int block = 1 << lmax;
    s.imax = int(std::ceil(std::max(count, 1.0) / block)) * block;
    return s;
}

std::pair<int, int> SliceRay::slices(const SliceSetup& s, double offset) const {
    if (!inside) return {1, 0};
    return {int(std::ceil((t0 - s.tNear) / s.spacing - offset)), int(std::floor((t1 - s.tNear) / s.spacing - offset))};
}

SliceRay sliceRayOf(const Ray& world, const Volume& volume, const SliceSetup& slices) {
    SliceRay r;
    r.dir = (volume.grid->transform().worldToIndex(world.origin + world.dir) - slices.eye).unitSafe();
    if (const auto ray = toIndexRay(world, volume)) r.inside = true, r.t0 = ray->t0, r.t1 = ray->t1;
    return r;
}

LevelRays makeLevelRays(const Camera& camera, const Volume& volume, const SliceSetup& slices, int level,
                        int paddedWidth, int paddedHeight, int imageWidth, int imageHeight) {
    LevelRays rays;
    const int scale = 1 << level;
    rays.width = paddedWidth / scale, rays.height = paddedHeight / scale;
    const std::size_t n = std::size_t(rays.width) * rays.height;
    rays.dir.resize(n), rays.first.resize(n), rays.last.resize(n);
    for (int y = 0; y < rays.height; ++y)
        for (int x = 0; x < rays.width; ++x) {
            const int i = rays.index(x, y);
            const SliceRay ray = sliceRayOf(camera.generate(scale * (x + 0.5), scale * (y + 0.5), imageWidth, imageHeight), volume, slices);
            rays.dir[i] = ray.dir;
            rays.first[i] = 1, rays.last[i] = 0;
            if (!ray.inside) continue;
            const auto [first, last] = ray.slices(slices);
            rays.first[i] = std::max(0, first), rays.last[i] = std::min(slices.imax, last);
        }
    return rays;
}

}  // namespace weft
