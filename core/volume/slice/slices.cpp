#include "core/volume/slice/slices.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

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

namespace {

// Nearest distance from `eye` (reference index space) to volume v's box:
// exact in v's own index space, scaled by a lower bound of the map's
// stretch (exact for a similarity), so slice 0 is never behind the box.
double nearDistance(const SliceVolume& v, const Vec3d& eye) {
    const Vec3d e = v.toOwn(eye);
    const openvdb::CoordBBox box = v.volume->indexBox();
    double sq = 0;
    for (int a = 0; a < 3; ++a) {
        const double lo = box.min()[a], hi = box.max()[a];
        const double dn = e[a] < lo ? lo - e[a] : e[a] > hi ? e[a] - hi : 0.0;
        sq += dn * dn;
    }
    const double l0 = v.axis[0].length(), l1 = v.axis[1].length(), l2 = v.axis[2].length();
    const double tol = 1e-9 * l0;
    const bool similar = std::abs(l0 - l1) <= tol && std::abs(l0 - l2) <= tol && std::abs(v.axis[0].dot(v.axis[1])) <= tol * l0 &&
                         std::abs(v.axis[0].dot(v.axis[2])) <= tol * l0 && std::abs(v.axis[1].dot(v.axis[2])) <= tol * l0;
    // own -> reference stretches by at least 1 / |reference -> own| (Frobenius norm when not a similarity).
    const double stretch = similar ? 1.0 / l0 : 1.0 / std::sqrt(l0 * l0 + l1 * l1 + l2 * l2);
    return std::sqrt(sq) * stretch;
}

// Farthest corner of volume v's box from `eye`, in reference index units.
double farDistance(const SliceVolume& v, const Volume& reference, const Vec3d& eye) {
    const openvdb::CoordBBox box = v.volume->indexBox();
    const auto &own = v.volume->grid->transform(), &ref = reference.grid->transform();
    double far = 0;
    for (int c = 0; c < 8; ++c) {
        const Vec3d corner((c & 1) ? box.max().x() : box.min().x(), (c & 2) ? box.max().y() : box.min().y(),
                           (c & 4) ? box.max().z() : box.min().z());
        far = std::max(far, (ref.worldToIndex(own.indexToWorld(corner)) - eye).length());
    }
    return far;
}

}  // namespace

SliceSetup makeSliceSetup(const Camera& camera, const std::vector<SliceVolume>& volumes, double spacing, int lmax) {
    const Volume& reference = *volumes.front().volume;
    SliceSetup s = makeSliceSetup(camera, reference, spacing, lmax);
    if (volumes.size() == 1) return s;
    double tNear = std::numeric_limits<double>::max(), tFar = 0;
    for (const SliceVolume& v : volumes) {
        if (v.volume->empty()) continue;
        tNear = std::min(tNear, nearDistance(v, s.eye)), tFar = std::max(tFar, farDistance(v, reference, s.eye));
    }
    if (tFar == 0) return s;
    s.tNear = tNear;
    const double count = std::ceil((tFar - s.tNear) / spacing);
    const int block = 1 << lmax;
    s.imax = int(std::ceil(std::max(count, 1.0) / block)) * block;
    return s;
}

LevelRays makeLevelRays(const Camera& camera, const std::vector<SliceVolume>& volumes, const SliceSetup& slices, int level,
                        int paddedWidth, int paddedHeight, int imageWidth, int imageHeight) {
    LevelRays rays = makeLevelRays(camera, *volumes.front().volume, slices, level, paddedWidth, paddedHeight, imageWidth, imageHeight);
    if (volumes.size() == 1) return rays;
    const std::size_t n = rays.dir.size();
    rays.first.resize(n * volumes.size()), rays.last.resize(n * volumes.size());
    const auto& ref = volumes.front().volume->grid->transform();
    const int scale = 1 << level;
    const CameraRays eye(camera, imageWidth, imageHeight);
    for (std::size_t k = 1; k < volumes.size(); ++k)
        tbb::parallel_for(0, rays.height, [&](int y) {
            for (int x = 0; x < rays.width; ++x) {
                const std::size_t i = std::size_t(rays.index(x, y)), at = k * n + i;
                const Ray world = eye.at(scale * (x + 0.5), scale * (y + 0.5));
                const auto ray = toIndexRay(world, *volumes[k].volume);
                rays.first[at] = 1, rays.last[at] = 0;
                if (!ray) continue;
                // Own index units -> reference ones: both per unit of the world ray's parameter.
                const double toRef = (ref.worldToIndex(world.origin + world.dir) - ref.worldToIndex(world.origin)).length() / ray->speed;
                rays.first[at] = std::max(0, int(std::ceil((ray->t0 * toRef - slices.tNear) / slices.spacing)));
                rays.last[at] = std::min(slices.imax, int(std::floor((ray->t1 * toRef - slices.tNear) / slices.spacing)));
            }
        });
    return rays;
}

LevelRays makeLevelRays(const Camera& camera, const Volume& volume, const SliceSetup& slices, int level,
                        int paddedWidth, int paddedHeight, int imageWidth, int imageHeight) {
    LevelRays rays;
    const int scale = 1 << level;
    rays.width = paddedWidth / scale, rays.height = paddedHeight / scale;
    const std::size_t n = std::size_t(rays.width) * rays.height;
    rays.dir.resize(n), rays.first.resize(n), rays.last.resize(n);
    const CameraRays eye(camera, imageWidth, imageHeight);  // one frame for every ray, as Camera::generate builds per call
    // Every ray starts at the slices' eye: only its direction goes to index space.
    const IndexDirections toIndex(volume);
    const openvdb::CoordBBox box = volume.indexBox();
    tbb::parallel_for(0, rays.height, [&](int y) {
        for (int x = 0; x < rays.width; ++x) {
            const int i = rays.index(x, y);
            SliceRay ray;
            ray.dir = toIndex(eye.at(scale * (x + 0.5), scale * (y + 0.5)).dir).unitSafe();
            if (!volume.empty())
                if (const auto span = clipToBox(slices.eye, ray.dir, box)) ray.inside = true, std::tie(ray.t0, ray.t1) = *span;
            rays.dir[i] = ray.dir;
            rays.first[i] = 1, rays.last[i] = 0;
            if (!ray.inside) continue;
            const auto [first, last] = ray.slices(slices);
            rays.first[i] = std::max(0, first), rays.last[i] = std::min(slices.imax, last);
        }
    });
    return rays;
}

}  // namespace weft
