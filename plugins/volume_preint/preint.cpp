// volume.preint — fixed-rate slice renderer with pre-integrated segments.
//
// Every ray is sampled on every slice (shells t_i = tNear + i * spacing, see
// core/volume/slices.hpp) and each segment between neighbouring slices is
// composited from a pre-integration table lookup (s_front, s_back, one
// slice). This is the "tex.-based" column of Kraus et al. 2007, Tables 2-3:
// the reference volume.adaptive3d is measured against at the same spacing.
//
// Camera samples come from the image plane (core/sampling/image_plane.hpp:
// pattern, filter, adaptive...), each one ray through every slice; the
// default is one ray through each pixel centre at 1 spp, as always.
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
// Counters: rays.camera, image.samples, slices, volume.samples (one trilinear lookup per
// slice inside the volume: the back sample of one segment is the front
// sample of the next), composite.ops; with meshes also rays.surface and
// rays.shadow.
#include <limits>

#include "core/lighting/delta_lights.hpp"
#include "core/lighting/surface_shading.hpp"
#include "core/sampling/image_plane.hpp"
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
    return withImagePlaneParams(std::move(specs));
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
    Preint(const Scene& scene, const ParamSet& p)
        : params_(readSliceParams(p)), offsetPattern_(p.getString("offset_pattern")), plane_(readImagePlaneOptions(p)) {
        requireSliceableVolume(scene, "volume.preint");
        requireSurfaceLights(scene, "volume.preint");
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        const Volume& vol = scene.volumes.front();
        const SliceSetup slices = makeSliceSetup(scene.camera, vol, params_.spacing, 0);
        SegmentTables tables(vol.tf, params_.spacing, 1, params_.tableResolution, params_.precision);
        std::optional<PatternSet> offsets;
        if (!offsetPattern_.empty()) offsets = makePatternSet(offsetPattern_, s.spp, hashCombine(s.seed, 0x0ff5));
        const MeshAccel* accel = scene.meshes.empty() ? nullptr : &scene.accel();  // built before the pixel loop
        if (accel) scene.emitters();
        const Frame frame{scene, vol, slices, tables.forSlices(1), offsets, accel, accel ? rayEpsilon(scene) : 0.0f, s};
        const ImagePlane plane(plane_, s);
        Image image = plane.render(ctx, "volume.preint", [&] { return Shader(frame); });
        ctx.counters.add(kSlices, slices.imax + 1);
        return image;
    }

private:
    // What every camera sample of one render shares.
    struct Frame {
        const Scene& scene;
        const Volume& vol;
        const SliceSetup& slices;
        const PreintegrationTable& table;
        const std::optional<PatternSet>& offsets;
        const MeshAccel* accel;
        float eps;
        const RenderSettings& s;
    };

    // One per row: a grid sampler and the counts. Each camera sample casts
    // one ray through every slice; at the pixel centre it is the ray the
    // renderer always cast there.
    struct Shader {
        const Frame& f;
        ScalarSampler sampler;
        std::int64_t rays = 0, samples = 0, composites = 0;
        SurfaceCounts surfaces;

        explicit Shader(const Frame& frame) : f(frame), sampler(frame.vol) {}
        Rgba operator()(const CameraSample& c) {
            const SliceSetup& slices = f.slices;
            const Ray worldRay = f.scene.camera.generate(c.x, c.y, f.s.width, f.s.height);
            const SliceRay ray = sliceRayOf(worldRay, f.vol, slices);
            const double shift = f.offsets ? f.offsets->sample(c.px, c.py, int(c.index % std::uint32_t(f.s.spp))).t : 0.0;
            const auto [first, last] = f.offsets ? ray.slices(slices, shift) : clamped(ray.slices(slices), slices);
            ++rays;
            const SurfaceHit hit = f.accel ? firstSurface(*f.accel, worldRay) : SurfaceHit{};
            const double tHit = surfaceDistance(f.vol, worldRay, hit);
            SegmentCompositor acc;
            // Segments wholly outside the volume are transparent: start one slice before it.
            const int from = f.offsets ? first - 1 : std::max(first - 1, 0), to = f.offsets ? last + 1 : std::min(last + 1, slices.imax);
            auto position = [&](int k) { return slices.t(k) + shift * slices.spacing; };
            auto scalarAt = [&](int k) {
                const bool inside = k >= first && k <= last;
                samples += inside;
                return inside ? sampler.sample(slices.eye + ray.dir * position(k)) : sampler.background();
            };
            float prev = scalarAt(from);
            for (int k = from + 1; k <= to; ++k) {
                if (position(k) > tHit) {  // the surface cuts this segment: its true length, exactly
                    const double length = tHit - position(k - 1);
                    if (length > 0) {
                        const float back = sampler.sample(slices.eye + ray.dir * tHit);
                        ++samples;
                        acc.add(PreintegrationTable::integrateSegment(f.vol.tf, prev, back, length));
                        ++composites;
                    }
                    break;
                }
                const float cur = scalarAt(k);
                acc.add(f.table.lookup(0, prev, cur));
                ++composites;
                prev = cur;
            }
            float px[4] = {acc.r, acc.g, acc.b, acc.a};
            if (hit.valid())
                shadeBehind(f.scene, *f.accel, worldRay, hit, PixelSampler(f.s.seed, c.px, c.py, c.index, std::uint32_t(f.s.spp)), f.eps, px, surfaces);
            return {px[0], px[1], px[2], px[3]};
        }
        void flush(Counters& counters) const {
            counters.add(kVolumeSamples, samples);
            counters.add(kCompositeOps, composites);
            counters.add(kRaysCamera, rays);
            if (!f.accel) return;  // mesh-free renders keep their counters as they were
            counters.add(kRaysSurface, surfaces.surface);
            counters.add(kRaysShadow, surfaces.shadow);
        }
    };

    static std::pair<int, int> clamped(std::pair<int, int> r, const SliceSetup& slices) {
        return {std::max(0, r.first), std::min(slices.imax, r.second)};
    }

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
    ImagePlaneOptions plane_;
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
