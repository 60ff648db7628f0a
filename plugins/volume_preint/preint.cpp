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
#include <climits>
#include <limits>

#include "core/lighting/delta_lights.hpp"
#include "core/lighting/surface_shading.hpp"
#include "core/sampling/pixel_loop.hpp"
#include "core/base/rng.hpp"
#include "core/sampling/pattern_set.hpp"
#include "core/volume/volume_ray.hpp"
#include "core/volume/segment_tables.hpp"
#include "core/volume/slice_volumes.hpp"
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

// Slices inside volume k on pixel (x, y)'s ray when they move `offset` spacings further.
std::pair<int, int> shiftedSlices(const Scene& scene, const SliceSetup& slices, int k, int x, int y, int w, int h, double offset) {
    const Ray world = scene.camera.generate(x + 0.5, y + 0.5, w, h);
    const auto ray = toIndexRay(world, scene.volumes[k]);
    if (!ray) return {1, 0};
    double toRef = 1;  // volume k's index units -> the reference volume's
    if (k > 0) {
        const auto& ref = scene.volumes.front().grid->transform();
        toRef = (ref.worldToIndex(world.origin + world.dir) - ref.worldToIndex(world.origin)).length() / ray->speed;
    }
    return {int(std::ceil((ray->t0 * toRef - slices.tNear) / slices.spacing - offset)),
            int(std::floor((ray->t1 * toRef - slices.tNear) / slices.spacing - offset))};
}

// Up to this many volumes per segment without a heap allocation.
constexpr int kMaxVolumes = 64;

// What one row's pixels share.
struct RowState {
    const std::vector<SliceVolume>& volumes;
    const SliceSetup& slices;
    const LevelRays& rays;
    std::vector<const PreintegrationTable*> tables;  // per volume, one slice long
    SliceSamplers samplers;
    std::int64_t samples = 0, composites = 0;
};

class Preint final : public Technique {
public:
    Preint(const Scene& scene, const ParamSet& p) : params_(readSliceParams(p)), offsetPattern_(p.getString("offset_pattern")) {
        requireSliceableVolume(scene, "volume.preint");
        requireSurfaceLights(scene, "volume.preint");
        if (scene.volumes.size() > std::size_t(kMaxVolumes))
            throw Error("volume.preint renders at most " + std::to_string(kMaxVolumes) + " volumes; the scene has " +
                        std::to_string(scene.volumes.size()));
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        const std::vector<SliceVolume> volumes = makeSliceVolumes(scene.volumes);
        const SliceSetup slices = makeSliceSetup(scene.camera, volumes, params_.spacing, 0);
        const LevelRays rays = makeLevelRays(scene.camera, volumes, slices, 0, s.width, s.height, s.width, s.height);
        SliceTables tables(volumes, params_.spacing, 1, params_.tableResolution, params_.precision);
        std::vector<const PreintegrationTable*> oneSlice;
        for (const SliceVolume& v : volumes) oneSlice.push_back(&tables.of(v).forSlices(1));
        Image image = Image::rgba(s.width, s.height);
        std::optional<PatternSet> offsets;
        if (!offsetPattern_.empty()) offsets = makePatternSet(offsetPattern_, 1, hashCombine(s.seed, 0x0ff5));
        const MeshAccel* accel = scene.meshes.empty() ? nullptr : &scene.accel();  // built before the pixel loop
        if (accel) scene.emitters();
        const float eps = accel ? rayEpsilon(scene) : 0.0f;
        forEachRow(s, "volume.preint", [&](int y) {
            RowState row{volumes, slices, rays, oneSlice, SliceSamplers(volumes)};
            SurfaceCounts surfaces;
            for (int x = 0; x < s.width; ++x) {
                Ray worldRay;
                SurfaceHit hit;
                if (accel) worldRay = scene.camera.generate(x + 0.5, y + 0.5, s.width, s.height), hit = firstSurface(*accel, worldRay);
                const double shift = offsets ? offsets->sample(x, y, 0).t : 0.0;
                const SegmentCompositor acc = pixel(scene, row, x, y, offsets.has_value(), shift,
                                                    surfaceIndexDistance(*volumes.front().volume, worldRay, hit));
                float* px = image.pixel(x, y);
                px[0] = acc.r, px[1] = acc.g, px[2] = acc.b, px[3] = acc.a;
                if (hit.valid()) compositeSurfaceBehind(scene, *accel, worldRay, hit, PixelSampler(s.seed, x, y, 0, 1), eps, px, surfaces);
            }
            ctx.counters.add("volume.samples", row.samples);
            ctx.counters.add("composite.ops", row.composites);
            ctx.counters.add("rays.camera", s.width);
            if (!accel) return;  // mesh-free renders keep their counters as they were
            ctx.counters.add("rays.surface", surfaces.surface);
            ctx.counters.add("rays.shadow", surfaces.shadow);
        });
        ctx.counters.add("slices", slices.imax + 1);
        return image;
    }

private:
    // One pixel's volumes, front to back, up to the surface at tHit (voxels; infinity: none).
    static SegmentCompositor pixel(const Scene& scene, RowState& row, int x, int y, bool shifted, double shift, double tHit) {
        const int n = int(row.volumes.size()), i = row.rays.index(x, y);
        const SliceSetup& slices = row.slices;
        int first[kMaxVolumes], last[kMaxVolumes];
        int from = INT_MAX, to = INT_MIN;  // segments wholly outside every volume are transparent
        for (int k = 0; k < n; ++k) {
            const auto [f, l] = shifted ? shiftedSlices(scene, slices, k, x, y, row.rays.width, row.rays.height, shift)
                                        : std::pair<int, int>(row.rays.firstOf(k, i), row.rays.lastOf(k, i));
            first[k] = f, last[k] = l;
            if (f > l && (k > 0 || n > 1)) continue;  // missed: widens nothing (one volume keeps its old bounds)
            from = std::min(from, shifted ? f - 1 : std::max(f - 1, 0)), to = std::max(to, shifted ? l + 1 : std::min(l + 1, slices.imax));
        }
        SegmentCompositor acc;
        if (from > to) return acc;
        const Vec3d dir = row.rays.dir[i];
        auto position = [&](int k) { return slices.t(k) + shift * slices.spacing; };
        float prev[kMaxVolumes], cur[kMaxVolumes];
        PreintSample seg[kMaxVolumes];
        auto scalars = [&](int k, float* s) {
            const Vec3d p = slices.eye + dir * position(k);
            for (int v = 0; v < n; ++v) {
                const bool inside = k >= first[v] && k <= last[v];
                row.samples += inside;
                s[v] = inside ? row.samplers.sample(v, p) : row.samplers.background(v);
            }
        };
        scalars(from, prev);
        for (int k = from + 1; k <= to; ++k) {
            if (position(k) > tHit) {  // the surface cuts this segment: its true length, exactly
                const double length = tHit - position(k - 1);
                if (length <= 0) break;
                const Vec3d p = slices.eye + dir * tHit;
                for (int v = 0; v < n; ++v)
                    seg[v] = exactSegment(row.volumes[v], prev[v], row.samplers.sample(v, p), length);
                row.samples += n;
                acc.add(combineMedia(seg, n));
                ++row.composites;
                break;
            }
            scalars(k, cur);
            for (int v = 0; v < n; ++v) seg[v] = row.tables[v]->lookup(0, prev[v], cur[v]), prev[v] = cur[v];
            acc.add(combineMedia(seg, n));
            ++row.composites;
        }
        return acc;
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
