#include "core/gbuffer.hpp"

#include <tbb/parallel_for.h>

#include <limits>

#include "core/brdf.hpp"
#include "core/mesh_accel.hpp"

namespace weft {

GBuffer createGBuffer(const Scene& scene, const RenderSettings& s, Counters& counters) {
    const MeshAccel& accel = scene.accel();
    GBuffer g;
    g.width = s.width, g.height = s.height;
    g.texels.resize(std::size_t(s.width) * s.height);
    tbb::parallel_for(0, s.height, [&](int y) {
        enableFastFloatMode();
        std::vector<RTCRayHit> rays(std::size_t(s.width));
        std::vector<Vec3f> dirs(std::size_t(s.width));
        for (int x = 0; x < s.width; ++x) {
            const Ray r = scene.camera.generate(x + 0.5, y + 0.5, s.width, s.height);
            dirs[x] = Vec3f(float(r.dir.x()), float(r.dir.y()), float(r.dir.z()));
            setRay(rays[x].ray, Vec3f(float(r.origin.x()), float(r.origin.y()), float(r.origin.z())), dirs[x], 0.0f,
                   std::numeric_limits<float>::infinity());
            rays[x].hit.geomID = RTC_INVALID_GEOMETRY_ID;
        }
        accel.intersectStream(rays.data(), unsigned(s.width), true);
        for (int x = 0; x < s.width; ++x) {
            const RTCRayHit& rh = rays[x];
            if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
            GTexel& t = g.at(x, y);
            const Vec3f ng = accel.normal(rh.hit.geomID, rh.hit.primID);
            t.front = ng.dot(dirs[x]) < 0;
            t.normal = t.front ? ng : -ng;
            t.position = Vec3f(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z) + dirs[x] * rh.ray.tfar;
            t.depth = rh.ray.tfar;
            t.material = std::int32_t(accel.material(rh.hit.geomID, rh.hit.primID));
            t.albedo = Brdf::of(scene.materials[std::size_t(t.material)]).kd;
        }
        counters.add("rays.camera", s.width);
    });
    return g;
}

}  // namespace weft
