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
            const Ray world = camera.generate(scale * (x + 0.5), scale * (y + 0.5), imageWidth, imageHeight);
            const auto ray = toIndexRay(world, volume);
            rays.dir[i] = (volume.grid->transform().worldToIndex(world.origin + world.dir) - slices.eye).unitSafe();
            rays.first[i] = 1, rays.last[i] = 0;
            if (!ray) continue;
            rays.first[i] = std::max(0, int(std::ceil((ray->t0 - slices.tNear) / slices.spacing)));
            rays.last[i] = std::min(slices.imax, int(std::floor((ray->t1 - slices.tNear) / slices.spacing)));
        }
    return rays;
}

}  // namespace weft
