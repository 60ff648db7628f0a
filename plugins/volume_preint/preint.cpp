// volume.preint — fixed-rate slice renderer with pre-integrated segments.
//
// Every ray is sampled on every slice (shells t_i = tNear + i * spacing, see
// core/volume/slice/slices.hpp) and each segment between neighbouring slices is
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
// Emission (a volume's emission grid: black-body temperature, emission
// times a colour) is read at every slice beside the data and varies
// linearly over a segment, like the data; the segment's emitted radiance,
// absorbed along it by the transfer function's extinction, comes from
// emission weights the table holds beside the colour (core/volume/optics/
// preintegration.hpp), built only when a volume emits. The cut segment in
// front of a surface integrates them exactly.
//
// Velocity motion blur: a moving volume (Volume::motion) is read, at every
// slice of a camera sample's ray, where its velocity advects the point from
// at the sample's shutter time (core/volume/volume_motion.hpp), so each
// sample sees the volume at one instant and spp samples cover the shutter
// as the camera-blurring techniques' do; segments between slices come from
// the same tables. The camera itself renders one instant.
//
// Several volumes (core/volume/slice/slice_volumes.hpp): slices are measured in
// the first volume's index space; every volume is sampled at each slice and
// overlapping segments combine as media whose extinctions add (combineMedia).
//
// Counters: rays.camera, image.samples, slices, volume.samples (one trilinear lookup per
// slice inside the volume, of the data and, where it emits, its emission: the back sample of one segment is the front
// sample of the next), composite.ops; with meshes also rays.surface and
// rays.shadow; with emission also preintegration.emission_tables.
#include <climits>
#include <limits>

#include "core/lighting/delta_lights.hpp"
#include "core/lighting/surface_shading.hpp"
#include "core/sampling/image_plane.hpp"
#include "core/base/rng.hpp"
#include "core/sampling/pattern_set.hpp"
#include "core/volume/volume_ray.hpp"
#include "core/volume/optics/segment_tables.hpp"
#include "core/volume/slice/slice_volumes.hpp"
#include "core/volume/slice/slices.hpp"
#include "core/volume/slice/slice_renderer.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

std::vector<ParamSpec> preintParams() {
    std::vector<ParamSpec> specs = sliceParamSpecs();
    specs.push_back(stringParam("offset_pattern", "",
                                "per-pixel slice offsets from a pattern set's third coordinate, e.g. "
                                "interleaved:4x4,basis=jittered (Keller & Heidrich 4.3); empty: none",
                                [](const std::string& v) { if (!v.empty()) validatePatternSpec(v); }));
    return withImagePlaneParams(std::move(specs), PlainSamples::Jittered);
}

// Up to this many volumes per segment without a heap allocation.
constexpr int kMaxVolumes = 64;

// Slices inside volume v on a camera ray when every slice moves `shift`
// spacings further; clamped to [0, imax] unless shifted (first > last: none).
std::pair<int, int> slicesIn(const SliceVolume& v, const Volume& reference, const Ray& world, const SliceSetup& s,
                             bool shifted, double shift) {
    const auto ray = toIndexRay(world, *v.volume);
    if (!ray) return {1, 0};
    double toRef = 1;  // own index units -> the reference's: both per unit of the world ray's parameter
    if (!v.reference) {
        const auto& ref = reference.grid->transform();
        toRef = (ref.worldToIndex(world.origin + world.dir) - ref.worldToIndex(world.origin)).length() / ray->speed;
    }
    const int first = int(std::ceil((ray->t0 * toRef - s.tNear) / s.spacing - shift));
    const int last = int(std::floor((ray->t1 * toRef - s.tNear) / s.spacing - shift));
    return shifted ? std::pair<int, int>(first, last) : std::pair<int, int>(std::max(0, first), std::min(s.imax, last));
}

class Preint final : public Technique {
public:
    Preint(const Scene& scene, const ParamSet& p)
        : params_(readSliceParams(p)), offsetPattern_(p.getString("offset_pattern")), plane_(readImagePlaneOptions(p, PlainSamples::Jittered)) {
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
        SliceTables tables(volumes, params_.spacing, 1, params_.tableResolution, params_.precision);
        std::vector<const PreintegrationTable*> oneSlice;
        for (const SliceVolume& v : volumes) {
            oneSlice.push_back(&tables.of(v).forSlices(1));
            oneSlice.back()->buildAll();  // every sample looks one up: build it whole, up front
        }
        std::optional<PatternSet> offsets;
        if (!offsetPattern_.empty()) offsets = makePatternSet(offsetPattern_, s.spp, hashCombine(s.seed, 0x0ff5));
        const MeshAccel* accel = scene.meshes.empty() ? nullptr : &scene.accel();  // built before the pixel loop
        if (accel) scene.emitters();
        const Frame frame{scene, volumes, slices, oneSlice, offsets, accel, accel ? rayEpsilon(scene) : 0.0f, sceneEmits(volumes),
                          scene.volumesMove(), s};
        const ImagePlane plane(plane_, s);
        Image image = plane.render(ctx, "volume.preint", [&] { return Shader(frame); });
        ctx.counters.add(kSlices, slices.imax + 1);
        if (const int n = tables.emissionBuiltCount()) ctx.counters.add(kEmissionTables, n);
        return image;
    }

private:
    // What every camera sample of one render shares.
    struct Frame {
        const Scene& scene;
        const std::vector<SliceVolume>& volumes;
        const SliceSetup& slices;
        const std::vector<const PreintegrationTable*>& tables;  // per volume, one slice long
        const std::optional<PatternSet>& offsets;
        const MeshAccel* accel;
        float eps;
        bool emits;  // some volume emits: its samples also read emission
        bool moves;  // some volume moves: each camera sample reads it at its shutter time
        const RenderSettings& s;
    };

    // One per row: the volumes' samplers and the counts. Each camera sample
    // casts one ray through every slice; at the pixel centre it is the ray
    // the renderer always cast there.
    struct Shader {
        const Frame& f;
        SliceSamplers samplers;
        std::int64_t rays = 0, samples = 0, composites = 0;
        SurfaceCounts surfaces;

        CameraRays eye;  // the camera's frame, built once per row instead of per ray

        explicit Shader(const Frame& frame) : f(frame), samplers(frame.volumes), eye(frame.scene.camera, frame.s.width, frame.s.height) {}
        Rgba operator()(const CameraSample& c) {
            const Volume& reference = *f.volumes.front().volume;
            const Ray worldRay = eye.at(c.x, c.y);
            const double shift = f.offsets ? f.offsets->sample(c.px, c.py, int(c.index % std::uint32_t(f.s.spp))).t : 0.0;
            ++rays;
            if (f.moves) samplers.setTime(f.scene.shutter.frameTime(0, c.time));
            const SurfaceHit hit = f.accel ? firstSurface(*f.accel, worldRay) : SurfaceHit{};
            const SegmentCompositor acc = march(worldRay, reference, shift, surfaceIndexDistance(reference, worldRay, hit));
            float px[4] = {acc.r, acc.g, acc.b, acc.a};
            if (hit.valid())
                compositeSurfaceBehind(f.scene, *f.accel, worldRay, hit, PixelSampler(f.s.seed, c.px, c.py, c.index, std::uint32_t(f.s.spp)),
                                       f.eps, px, surfaces);
            return {px[0], px[1], px[2], px[3]};
        }

        // The ray's volumes, front to back, up to the surface at tHit (reference voxels; infinity: none).
        SegmentCompositor march(const Ray& worldRay, const Volume& reference, double shift, double tHit) {
            const int n = int(f.volumes.size());
            const SliceSetup& slices = f.slices;
            const bool shifted = f.offsets.has_value();
            int first[kMaxVolumes], last[kMaxVolumes];
            int from = INT_MAX, to = INT_MIN;  // segments wholly outside every volume are transparent
            for (int k = 0; k < n; ++k) {
                std::tie(first[k], last[k]) = slicesIn(f.volumes[k], reference, worldRay, slices, shifted, shift);
                if (first[k] > last[k] && n > 1) continue;  // missed: widens nothing (one volume keeps its old bounds)
                from = std::min(from, shifted ? first[k] - 1 : std::max(first[k] - 1, 0));
                to = std::max(to, shifted ? last[k] + 1 : std::min(last[k] + 1, slices.imax));
            }
            SegmentCompositor acc{};
            if (from > to) return acc;
            const Vec3d dir = sliceRayOf(worldRay, reference, slices).dir;
            auto position = [&](int k) { return slices.t(k) + shift * slices.spacing; };
            float prev[kMaxVolumes], cur[kMaxVolumes];
            Vec3f ePrev[kMaxVolumes], eCur[kMaxVolumes];  // emission, read only when the scene emits
            PreintSample seg[kMaxVolumes];
            auto scalars = [&](int k, float* s, Vec3f* e) {
                const Vec3d p = slices.eye + dir * position(k);
                for (int v = 0; v < n; ++v) {
                    const bool inside = k >= first[v] && k <= last[v];
                    samples += inside;
                    s[v] = inside ? samplers.sample(v, p) : samplers.background(v);
                    if (f.emits) e[v] = inside ? samplers.emission(v, p) : Vec3f(0.0f);
                }
            };
            scalars(from, prev, ePrev);
            for (int k = from + 1; k <= to; ++k) {
                if (position(k) > tHit) {  // the surface cuts this segment: its true length, exactly
                    const double length = tHit - position(k - 1);
                    if (length <= 0) break;
                    const Vec3d p = slices.eye + dir * tHit;
                    for (int v = 0; v < n; ++v)
                        seg[v] = f.emits ? exactEmittingSegment(f.volumes[v], prev[v], samplers.sample(v, p), ePrev[v], samplers.emission(v, p), length)
                                         : exactSegment(f.volumes[v], prev[v], samplers.sample(v, p), length);
                    samples += n;
                    acc.add(combineMedia(seg, n));
                    ++composites;
                    break;
                }
                scalars(k, cur, eCur);
                for (int v = 0; v < n; ++v) {
                    seg[v] = f.tables[v]->lookupComplete(0, prev[v], cur[v]);
                    if (f.emits && (ePrev[v] != Vec3f(0.0f) || eCur[v] != Vec3f(0.0f)))
                        addEmission(seg[v], f.tables[v]->lookupEmission(0, prev[v], cur[v]), ePrev[v], eCur[v]);
                    prev[v] = cur[v], ePrev[v] = eCur[v];
                }
                acc.add(combineMedia(seg, n));
                ++composites;
            }
            return acc;
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
    /*bytesPerPixel=*/32,
    /*reference=*/{"volume.raymarch", {"step=0.1"}, 256},
    /*knobs=*/{{"spacing", {"4", "2", "1", "0.5"}}, {"table_res", {"64", "256"}}, {"spp", {"1", "4", "16", "64"}}},
    /*scatters=*/false,
    /*velocityBlur=*/true,
    /*emission=*/true,
}};

}  // namespace

}  // namespace weft
