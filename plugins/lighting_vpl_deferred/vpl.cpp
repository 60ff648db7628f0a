#include "plugins/lighting_vpl_deferred/vpl.hpp"

#include <tbb/parallel_for.h>

#include <limits>

#include "core/lighting/delta_lights.hpp"
#include "core/lighting/emitters.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/base/rng.hpp"
#include "core/sampling/pixel_sampler.hpp"

namespace weft {

namespace {

// A light source to start paths from: the emitters (index -1) or a scene light.
struct Source {
    int light = -1;
    float pdf = 0;
};

std::vector<Source> sourcesByPower(const Scene& scene, float diskRadius) {
    std::vector<Source> out;
    std::vector<float> power;
    if (!scene.emitters().empty()) out.push_back({-1, 0}), power.push_back(luminance(scene.emitters().power()));
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        const float e = float(l.intensity) * luminance(l.color);
        out.push_back({int(i), 0});
        power.push_back(l.type == LightType::Point ? float(4 * M_PI) * e : float(M_PI) * diskRadius * diskRadius * e);
    }
    float total = 0;
    for (float p : power) total += p;
    for (std::size_t i = 0; i < out.size(); ++i) out[i].pdf = total > 0 ? power[i] / total : 1.0f / float(out.size());
    return out;
}

const Source& pickSource(const std::vector<Source>& sources, float u) {
    for (const Source& s : sources) {
        if (u < s.pdf) return s;
        u -= s.pdf;
    }
    return sources.back();
}

struct PathStart {
    Vec3f origin, dir, beta;
    bool valid = false;
};

}  // namespace

VplSet generateVpls(const Scene& scene, std::uint32_t paths, std::uint64_t seed, const VolumeAttenuation& volumes,
                    Counters& counters) {
    const MeshAccel& accel = scene.accel();
    const Emitters& emitters = scene.emitters();
    const BBoxd box = scene.worldBox();
    const float radius = float(0.5 * box.extents().length());
    const Vec3d c = box.getCenter();
    const Vec3f center(float(c.x()), float(c.y()), float(c.z()));
    const float eps = rayEpsilon(scene);
    const std::vector<Source> sources = sourcesByPower(scene, radius);

    std::vector<Vpl> emitterVpl(paths), bounceVpl(paths);
    std::vector<char> hasEmitter(paths, 0), hasBounce(paths, 0);
    if (!sources.empty())
        tbb::parallel_for(std::uint32_t(0), paths, [&](std::uint32_t k) {
            enableFastFloatMode();
            Rng rng(hashCombine(seed ^ 0x76706c73ull, k));
            const Source& src = pickSource(sources, rng.uniform());
            PathStart start;
            if (src.light < 0) {
                // Drawn one by one: the order of a call's arguments is unspecified
                // (gcc evaluated them right to left, clang left to right), and the
                // image must not depend on the compiler. This is gcc's order.
                const float u2 = rng.uniform(), u1 = rng.uniform(), u0 = rng.uniform();
                const EmitterSample e = emitters.sample((float(k) + u0) / float(paths), u1, u2);
                const float pdf = src.pdf * e.pdfArea;
                emitterVpl[k] = {e.position, e.normal, e.radiance / pdf, Vec3f(0, 0, 0), -1, VplKind::Emitter, k};
                hasEmitter[k] = 1;
                const float u = rng.uniform(), v = rng.uniform();
                start = {e.position + e.normal * eps, sampleCosine(e.normal, u, v), e.radiance * float(M_PI) / pdf, true};
            } else {
                const Light& l = scene.lights[std::size_t(src.light)];
                const Vec3f power = l.color * float(l.intensity) / src.pdf;
                const float u = rng.uniform(), v = rng.uniform();
                if (l.type == LightType::Point) {
                    start = {Vec3f(float(l.position.x()), float(l.position.y()), float(l.position.z())), sampleSphere(u, v), power * float(4 * M_PI), true};
                } else {  // directional: parallel rays through a disk covering the scene
                    const Vec3f d(float(l.direction.x()), float(l.direction.y()), float(l.direction.z()));
                    const float r = radius * std::sqrt(u), phi = float(2 * M_PI) * v;
                    const Frame f(d);
                    start = {center - d * (2 * radius) + f.t * (r * std::cos(phi)) + f.b * (r * std::sin(phi)), d,
                             power * float(M_PI) * radius * radius, true};
                }
            }
            const SurfaceHit hit = accel.intersect(start.origin, start.dir, 0.0f, std::numeric_limits<float>::infinity());
            if (!hit.valid()) return;
            const Vec3f n = hit.normal.dot(start.dir) < 0 ? hit.normal : -hit.normal;
            if (volumes.active()) {
                SegmentAttenuation segment(volumes);
                start.beta *= segment.along(start.origin, start.dir, hit.t);
                segment.report(counters);
            }
            bounceVpl[k] = {start.origin + start.dir * hit.t, n, start.beta, -start.dir,
                            std::int32_t(accel.material(hit.geom, hit.prim)), VplKind::Bounce, k};
            hasBounce[k] = 1;
        });
    VplSet set;
    set.paths = paths;
    set.rays = paths;
    for (std::uint32_t k = 0; k < paths; ++k) {
        if (hasEmitter[k]) set.vpls.push_back(emitterVpl[k]), ++set.emitterCount;
        if (hasBounce[k]) set.vpls.push_back(bounceVpl[k]), ++set.bounceCount;
    }
    return set;
}

bool shadeWithVpl(const Vpl& vpl, const ShadeTexel& t, const Vec3f& eye, const std::vector<Brdf>& brdfs, float gmax, VplShading& out) {
    Vec3f to = vpl.position - t.position;
    const float d2 = to.lengthSqr();
    if (!(d2 > 0)) return false;
    const float d = std::sqrt(d2);
    to /= d;
    const float cosX = t.normal.dot(to);
    const float cosY = -vpl.normal.dot(to);
    if (cosX <= 0 || cosY <= 0) return false;
    Vec3f radiance;
    if (vpl.kind == VplKind::Emitter) {
        radiance = vpl.weight * (cosX * cosY / d2);
    } else {
        const Brdf& fy = brdfs[std::size_t(vpl.material)];
        radiance = vpl.weight * fy.eval(-to, vpl.wi, vpl.normal) * std::min(cosX * cosY / d2, gmax);
    }
    const Brdf& fx = brdfs[std::size_t(t.material)];
    out.d = radiance * float(1 / M_PI);
    out.s = fx.glossy() ? radiance * fx.lobe((eye - t.position).unitSafe(), to, t.normal) : Vec3f(0, 0, 0);
    out.toLight = to;
    out.distance = d;
    return true;
}

}  // namespace weft
