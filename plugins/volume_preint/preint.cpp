// volume.preint — fixed-rate slice renderer with pre-integrated segments.
//
// Every ray is sampled on every slice (shells t_i = tNear + i * spacing, see
// core/volume/slices.hpp) and each segment between neighbouring slices is
// composited from a pre-integration table lookup (s_front, s_back, one
// slice). This is the "tex.-based" column of Kraus et al. 2007, Tables 2-3:
// the reference volume.adaptive3d is measured against at the same spacing.
//
// offset_pattern (optional) moves every slice of pixel (x, y) by a fraction
// of the spacing taken from a pattern set's third coordinate, e.g.
// interleaved:4x4,basis=jittered: the 16 pixels of each tile sample 16
// different strata between slices (Keller & Heidrich 2001, 4.3), which turns
// slicing artefacts into fine structured noise. Segments stay one spacing
// long, so the same table serves.
//
// Meshes: each pixel's ray ends at its first surface. Whole segments in
// front of it come from the table; the segment the surface cuts is
// integrated from its front slice to the surface with its true length
// (PreintegrationTable::integrateSegment, exact, so no table is built for
// lengths used once), its back scalar read at the surface. The surface is
// shaded and composited as in volume.raymarch (core/lighting/surface_shading.hpp):
// colour = volume + (1 - alpha) x surface, alpha 1; the volume does not
// shadow surfaces.
//
// Counters: rays.camera, slices, volume.samples (one trilinear lookup per
// slice inside the volume: the back sample of one segment is the front
// sample of the next), composite.ops; with meshes also rays.surface and
// rays.shadow.
#include <limits>

#include "core/lighting/delta_lights.hpp"
#include "core/lighting/surface_shading.hpp"
#include "core/sampling/pixel_loop.hpp"
#include "core/base/rng.hpp"
#include "core/sampling/pattern_set.hpp"
#include "core/volume/volume_ray.hpp"
#include "core/volume/segment_tables.hpp"
#include "core/volume/slices.hpp"
#include "core/volume/slice_renderer.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

std::vector<ParamSpec> preintParams() {
    std::vector<ParamSpec> specs = sliceParamSpecs();
    specs.push_back(stringParam("offset_pattern", "",
                                "per-pixel slice offsets from a pattern set's third coordinate, e.g. "
                                "interleaved:4x4,basis=jittered (Keller & Heidrich 4.3); empty: none",
                                [](const std::string& v) { if (!v.empty()) validatePatternSpec(v); }));
    return specs;
}

// Slices inside the volume on pixel (x, y)'s ray when they move `offset` spacings further.
std::pair<int, int> shiftedSlices(const Scene& scene, const SliceSetup& slices, int x, int y, int w, int h, double offset) {
    const auto ray = toIndexRay(scene.camera.generate(x + 0.5, y + 0.5, w, h), scene.volumes.front());
    if (!ray) return {1, 0};
    return {int(std::ceil((ray->t0 - slices.tNear) / slices.spacing - offset)),
            int(std::floor((ray->t1 - slices.tNear) / slices.spacing - offset))};
}

// Index-space distance from the eye to the first surface on the pixel's ray (infinity: none).
double surfaceDistance(const Volume& vol, const Ray& ray, const SurfaceHit& hit) {
    if (!hit.valid()) return std::numeric_limits<double>::infinity();
    const auto& xf = vol.grid->transform();
    return double(hit.t) * (xf.worldToIndex(ray.origin + ray.dir) - xf.worldToIndex(ray.origin)).length();
}

struct SurfaceCounts {
    std::int64_t surface = 0, shadow = 0;
};

class Preint final : public Technique {
public:
    Preint(const Scene& scene, const ParamSet& p) : params_(readSliceParams(p)), offsetPattern_(p.getString("offset_pattern")) {
        requireSliceableVolume(scene, "volume.preint");
        requireSurfaceLights(scene, "volume.preint");
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        const Volume& vol = scene.volumes.front();
        const SliceSetup slices = makeSliceSetup(scene.camera, vol, params_.spacing, 0);
        const LevelRays rays = makeLevelRays(scene.camera, vol, slices, 0, s.width, s.height, s.width, s.height);
        SegmentTables tables(vol.tf, params_.spacing, 1, params_.tableResolution, params_.precision);
        const PreintegrationTable& table = tables.forSlices(1);
        Image image = Image::rgba(s.width, s.height);
        std::optional<PatternSet> offsets;
        if (!offsetPattern_.empty()) offsets = makePatternSet(offsetPattern_, 1, hashCombine(s.seed, 0x0ff5));
        const MeshAccel* accel = scene.meshes.empty() ? nullptr : &scene.accel();  // built before the pixel loop
        if (accel) scene.emitters();
        const float eps = accel ? rayEpsilon(scene) : 0.0f;
        forEachRow(s, "volume.preint", [&](int y) {
            ScalarSampler sampler(vol);
            std::int64_t samples = 0, composites = 0;
            SurfaceCounts surfaces;
            for (int x = 0; x < s.width; ++x) {
                const int i = rays.index(x, y);
                SegmentCompositor acc;
                const double shift = offsets ? offsets->sample(x, y, 0).t : 0.0;
                const auto [first, last] = offsets ? shiftedSlices(scene, slices, x, y, s.width, s.height, shift)
                                                   : std::pair<int, int>(rays.first[i], rays.last[i]);
                Ray worldRay;
                SurfaceHit hit;
                if (accel) worldRay = scene.camera.generate(x + 0.5, y + 0.5, s.width, s.height), hit = firstSurface(*accel, worldRay);
                const double tHit = surfaceDistance(vol, worldRay, hit);
                // Segments wholly outside the volume are transparent: start one slice before it.
                const int from = offsets ? first - 1 : std::max(first - 1, 0), to = offsets ? last + 1 : std::min(last + 1, slices.imax);
                auto position = [&](int k) { return slices.t(k) + shift * slices.spacing; };
                auto scalarAt = [&](int k) {
                    const bool inside = k >= first && k <= last;
                    samples += inside;
                    return inside ? sampler.sample(slices.eye + rays.dir[i] * position(k)) : sampler.background();
                };
                float prev = scalarAt(from);
                for (int k = from + 1; k <= to; ++k) {
                    if (position(k) > tHit) {  // the surface cuts this segment: its true length, exactly
                        const double length = tHit - position(k - 1);
                        if (length > 0) {
                            const float back = sampler.sample(slices.eye + rays.dir[i] * tHit);
                            ++samples;
                            acc.add(PreintegrationTable::integrateSegment(vol.tf, prev, back, length));
                            ++composites;
                        }
                        break;
                    }
                    const float cur = scalarAt(k);
                    acc.add(table.lookup(0, prev, cur));
                    ++composites;
                    prev = cur;
                }
                float* px = image.pixel(x, y);
                px[0] = acc.r, px[1] = acc.g, px[2] = acc.b, px[3] = acc.a;
                if (hit.valid()) shadeBehind(scene, *accel, worldRay, hit, PixelSampler(s.seed, x, y, 0, 1), eps, px, surfaces);
            }
            ctx.counters.add(kVolumeSamples, samples);
            ctx.counters.add(kCompositeOps, composites);
            ctx.counters.add(kRaysCamera, s.width);
            if (!accel) return;  // mesh-free renders keep their counters as they were
            ctx.counters.add(kRaysSurface, surfaces.surface);
            ctx.counters.add(kRaysShadow, surfaces.shadow);
        });
        ctx.counters.add(kSlices, slices.imax + 1);
        return image;
    }

private:
    // The surface seen through the volume's pixel px (premultiplied RGBA).
    static void shadeBehind(const Scene& scene, const MeshAccel& accel, const Ray& ray, const SurfaceHit& hit,
                            const PixelSampler& sampler, float eps, float* px, SurfaceCounts& counts) {
        ++counts.surface;
        const Vec3f L = shadeSurface(scene, accel, ray, hit, sampler, eps, counts.shadow);
        const float T = 1.0f - px[3];
        px[0] += T * L.x(), px[1] += T * L.y(), px[2] += T * L.z(), px[3] = 1.0f;
    }

    SliceParams params_;
    std::string offsetPattern_;
};

const TechniqueRegistrar registrar{{
    "volume.preint",
    "fixed-rate slices with pre-integrated segments (Kraus et al. 2007, the tex.-based reference)",
    ParamTable("volume.preint", preintParams()),
    [](const Scene& scene, const ParamSet& p) { return std::make_unique<Preint>(scene, p); },
    /*motionBlur=*/false,
    /*renders=*/Content::VolumesAndMeshes,
}};

}  // namespace

}  // namespace weft
