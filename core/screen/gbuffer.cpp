#include "core/screen/gbuffer.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/screen/atrous.hpp"
#include "core/lighting/brdf.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/sampling/image_plane.hpp"

namespace weft {

namespace {

// Fills the texel of one pixel from its primary ray's hit.
void fillTexel(const Scene& scene, const MeshAccel& accel, const Vec3f& origin, const Vec3f& dir, float t,
               unsigned geom, unsigned prim, GTexel& out) {
    const Vec3f ng = accel.normal(geom, prim);
    out.front = ng.dot(dir) < 0;
    out.normal = out.front ? ng : -ng;
    out.position = origin + dir * t;
    out.depth = t;
    out.material = std::int32_t(accel.material(geom, prim));
    out.albedo = Brdf::of(scene.materials[std::size_t(out.material)]).kd;
}

constexpr int kTile = 4;  // 4x4 pixels: one 16-ray Embree packet

// Camera::generate with its frame computed once per image (same arithmetic, same rays).
struct PixelRays {
    Vec3d eye, forward, right, up;
    double tanHalf, aspect;
    int width, height;
    PixelRays(const Camera& c, int w, int h) : eye(c.eye), width(w), height(h) {
        forward = (c.target - c.eye).unitSafe();
        right = forward.cross(c.up).unitSafe();
        up = right.cross(forward);
        tanHalf = std::tan(0.5 * c.fovY * M_PI / 180.0);
        aspect = double(w) / double(h);
    }
    Vec3d dir(double px, double py) const {
        const double sx = (2.0 * px / width - 1.0) * tanHalf * aspect;
        const double sy = (1.0 - 2.0 * py / height) * tanHalf;
        return (forward + right * sx + up * sy).unitSafe();
    }
};

}  // namespace

GBuffer createGBuffer(const Scene& scene, const RenderSettings& s, Counters& counters) {
    const MeshAccel& accel = scene.accel();
    GBuffer g;
    g.width = s.width, g.height = s.height;
    g.texels.resize(std::size_t(s.width) * s.height);
    const int tileRows = (s.height + kTile - 1) / kTile;
    const PixelRays camera(scene.camera, s.width, s.height);
    // The image plane's camera samples at 1 spp: the pixel centres.
    RenderSettings single = s;
    single.spp = 1;
    const ImagePlane plane(ImagePlaneOptions{}, single);
    const Vec3f origin(float(camera.eye.x()), float(camera.eye.y()), float(camera.eye.z()));
    tbb::parallel_for(0, tileRows, [&](int ty) {
        enableFastFloatMode();
        for (int x0 = 0; x0 < s.width; x0 += kTile) {
            alignas(64) RTCRayHit16 rh;
            alignas(64) int valid[16];
            Vec3f dirs[16];
            for (int i = 0; i < 16; ++i) {
                const int x = std::min(x0 + i % kTile, s.width - 1), y = std::min(ty * kTile + i / kTile, s.height - 1);
                valid[i] = (x0 + i % kTile < s.width && ty * kTile + i / kTile < s.height) ? -1 : 0;
                const CameraSample c = plane.sample(x, y, 0);
                const Vec3d d = camera.dir(c.x, c.y);
                dirs[i] = Vec3f(float(d.x()), float(d.y()), float(d.z()));
                rh.ray.org_x[i] = origin.x(), rh.ray.org_y[i] = origin.y(), rh.ray.org_z[i] = origin.z();
                rh.ray.dir_x[i] = dirs[i].x(), rh.ray.dir_y[i] = dirs[i].y(), rh.ray.dir_z[i] = dirs[i].z();
                rh.ray.tnear[i] = 0, rh.ray.tfar[i] = std::numeric_limits<float>::infinity(), rh.ray.time[i] = 0;
                rh.ray.mask[i] = 0xFFFFFFFFu, rh.ray.id[i] = unsigned(i), rh.ray.flags[i] = 0;
                rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
            }
            accel.intersectPacket(valid, rh);
            for (int i = 0; i < 16; ++i) {
                if (!valid[i] || rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
                fillTexel(scene, accel, origin, dirs[i], rh.ray.tfar[i], rh.hit.geomID[i], rh.hit.primID[i],
                          g.at(x0 + i % kTile, ty * kTile + i / kTile));
            }
        }
        counters.add(kRaysCamera, std::int64_t(s.width) * std::min(kTile, s.height - ty * kTile));
    });
    return g;
}

GeometryGuides guidesOf(const GBuffer& g) {
    GeometryGuides out{g.width, g.height, {}, {}};
    // A plane per task, made and filled by one thread: six planes' pages
    // are first touched on every thread instead of all on one.
    tbb::parallel_for(0, 6, [&](int k) {
        std::vector<float>& plane = k < 3 ? out.normal.c[std::size_t(k)] : out.position.c[std::size_t(k - 3)];
        plane.resize(g.texels.size());
        for (std::size_t i = 0; i < g.texels.size(); ++i) plane[i] = k < 3 ? g.texels[i].normal[k] : g.texels[i].position[k - 3];
    });
    return out;
}

}  // namespace weft
