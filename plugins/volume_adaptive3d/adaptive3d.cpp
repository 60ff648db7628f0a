// volume.adaptive3d — oracle-based adaptive sampling in three dimensions
// (Kraus, Strengert, Klein, Ertl 2007).
//
// An oracle (oracles/) gives a sampling distance d everywhere. Slices are
// processed front to back (core/volume/slice/slices.hpp); slice i starts at pyramid level
// l_slice = min(trailing zeros of i, lmax) and walks down to level 0
// (Figure 4). On each level a pixel
//   - is synthesised from the coarser level (Figures 5-7: bilinear weights
//     9/16, 3/16, 3/16, 1/16) when l < l_slice and it is due on this slice
//     (l_slice = lmax, or its stored d < 2^(l_slice+1));
//   - samples data and oracle when l = lmax or d < 2^(l+1);
//   - on level 0, composites the segment since its previous composite with
//     the pre-integration table for that many slices (Figure 8) when
//     l_slice = lmax or d < 2^(l_slice+1).
// So a ray skips samples while d >= 2^(l_slice+1), never sampling more
// sparsely than the oracle asked, and image-plane neighbours share coarse
// samples where the oracle allows. Decisions use the distance held before
// this slice's sample replaces it (as the depth values of Figure 9 do), so
// every level-0 sample is composited.
//
// Emission: each sample reads the volume's emission grid too (synthesised
// like the data on coarser levels) and a segment's emitted radiance, linear
// between its ends and absorbed along it, comes from the table's emission
// weights (core/volume/optics/preintegration.hpp), as in volume.preint; they are
// built only when a volume emits. The oracles see emission as a feature
// where one slice's emitted radiance changes by more than epsilon per voxel
// (oracles/feature_distance.hpp), so a glowing region is never skipped as
// if empty; the oracle cache keys an emitting volume by its emission too.
//
// Velocity motion blur: a moving volume (Volume::motion) is rendered in spp
// passes, each at one shutter time (stratified, one jitter per seed) and
// averaged with equal weights; a pass reads the volume where its velocity
// advects each point from (core/volume/volume_motion.hpp). The pyramid
// synthesises pixels from their neighbours' samples, so a pass shares one
// instant. The oracle field is read at the unmoved point: its distances
// shrink by the volume's reach (oracles/oracle.hpp: paddedByReach), so no
// skip passes a feature wherever the velocity carried it.
//
// Meshes: each pixel's ray ends at its first surface (Embree, built only
// when the scene has meshes). Skipping never passes it (SliceWorker::
// surfaceBound): a pixel composites on its last slice in front of the
// surface, then the cut segment with its true length, exactly as
// volume.preint does; coarse pixels stop at the nearest surface of their
// footprint and are refined where its surfaces differ in depth. The
// surface is shaded and composited behind (core/lighting/surface_shading.hpp)
// with --spp light samples at the pixel centre (the volume pass is one
// unless a volume moves).
//
// Counters (the paper's operations): volume.samples (SAMPLE DATA),
// oracle.samples (SAMPLE ORACLE), synthesis.ops (SYNTHESIZE DATA+ORACLE of
// one pixel), composite.ops (ACCUMULATE COLOR of a segment), slices; with
// meshes also rays.surface and rays.shadow; with emission also
// preintegration.emission_tables. oracle.built / oracle.reused say
// whether each volume's oracle field was built or found built by an earlier
// render of the process (oracles/oracle_cache.hpp: frames, sweeps).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <optional>

#include "core/base/run/progress.hpp"
#include "core/base/rng.hpp"
#include "core/lighting/delta_lights.hpp"
#include "core/lighting/surface_shading.hpp"
#include "core/volume/optics/segment_tables.hpp"
#include "core/volume/slice/slices.hpp"
#include "oracles/oracle_cache.hpp"
#include "core/volume/slice/slice_renderer.hpp"
#include "plugins/technique.hpp"
#include "plugins/volume_adaptive3d/pyramid.hpp"

namespace weft {

namespace {

const Counter kPreintegrationTables{"preintegration.tables", "pre-integration tables built"};
const Counter kPreintegrationEntries{"preintegration.entries", "pre-integration table entries integrated (in blocks, where lookups needed them)"};
const Counter kOracleBuilt{"oracle.built", "oracle fields built by this render (one per volume)"};
const Counter kShutterPasses{"shutter.passes", "volume passes at distinct shutter times (spp of them when a volume moves)"};
const Counter kOracleReused{"oracle.reused", "oracle fields reused from an earlier render of this process (same volume, emission, transfer function, spacing, lmax, epsilon)"};

struct AdaptiveParams {
    SliceParams slice;
    std::string oracle;
    int lmax;
    double epsilon;
};

class Adaptive3d final : public Technique {
public:
    Adaptive3d(const Scene& scene, const ParamSet& p)
        : params_{readSliceParams(p), p.getString("oracle"), int(p.getInt("lmax")), p.getFloat("epsilon")},
          oracle_(oracles().get(params_.oracle)) {
        requireSliceableVolume(scene, "volume.adaptive3d");
        requireSurfaceLights(scene, "volume.adaptive3d");
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        const std::vector<SliceVolume> volumes = makeSliceVolumes(scene.volumes);
        const Volume& vol = scene.volumes.front();
        const int block = 1 << params_.lmax;
        const int pw = (s.width + block - 1) / block * block, ph = (s.height + block - 1) / block * block;
        const SliceSetup slices = makeSliceSetup(scene.camera, volumes, params_.slice.spacing, params_.lmax);
        const std::vector<OracleField> fields = oracleFields(volumes, ctx);
        const MeshAccel* accel = scene.meshes.empty() ? nullptr : &scene.accel();  // no BVH without meshes
        Surfaces surfaces;
        if (accel) surfaces = traceSurfaces(scene, *accel, vol, pw, ph, s);
        SliceTables tables(volumes, params_.slice.spacing, block, params_.slice.tableResolution, params_.slice.precision);
        const std::vector<double> times = shutterTimes(scene, s);
        Progress progress("volume.adaptive3d", std::int64_t(slices.imax + 1) * std::int64_t(times.size()), s.monitor);
        Image image;
        for (double time : times) {
            std::optional<Pyramid> pyramid;
            {
                ScopedTimer timer(ctx.timings, "pyramid");
                pyramid.emplace(scene.camera, volumes, slices, params_.lmax, pw, ph, s.width, s.height);
                if (accel) pyramid->setSurfaces(surfaces.tHit, slices);
            }
            SliceContext sc{volumes, fields, slices, tables, params_.lmax, ctx.counters, time};
            SliceWorkers workers(sc);
            {
                ScopedTimer timer(ctx.timings, "slices");
                for (int i = 0; i <= slices.imax; ++i) {
                    projectSlice(*pyramid, workers, i);
                    progress.advance();
                }
            }
            workers.flush();
            accumulate(image, pyramid->image(s.width, s.height), times.size());
        }
        progress.finish();
        ctx.counters.add(kSlices, slices.imax + 1);
        ctx.counters.add(kPreintegrationTables, tables.builtCount());
        ctx.counters.add(kPreintegrationEntries, tables.entriesBuilt());
        if (const int n = tables.emissionBuiltCount()) ctx.counters.add(kEmissionTables, n);
        if (scene.volumesMove()) ctx.counters.add(kShutterPasses, std::int64_t(times.size()));
        if (accel) shadeSurfaces(scene, *accel, surfaces.hits, pw, image, ctx);
        return image;
    }

private:
    // Each volume's oracle field, from the process's cache when built before;
    // a moving volume's padded by its reach (it is read advected).
    std::vector<OracleField> oracleFields(const std::vector<SliceVolume>& volumes, RenderContext& ctx) const {
        ScopedTimer timer(ctx.timings, "oracle");
        std::vector<OracleField> fields;
        for (const SliceVolume& v : volumes) {
            const double spacing = params_.slice.spacing * v.lengthScale;
            SharedOracleField shared = sharedOracleField(oracle_, {*v.volume, spacing, params_.lmax, params_.epsilon});
            ctx.counters.add(shared.reused ? kOracleReused : kOracleBuilt, 1);
            fields.push_back(paddedByReach(shared.field, v.volume->motionReach, spacing));
        }
        return fields;
    }

    // The shutter times of the volume passes: one instant when nothing moves,
    // else spp passes, stratified over the shutter with one jitter per seed
    // (a pass shares its instant: the pyramid synthesises rays from
    // neighbours, which must see the volume at the same time).
    static std::vector<double> shutterTimes(const Scene& scene, const RenderSettings& s) {
        if (!scene.volumesMove()) return {0.0};
        const int n = std::max(1, s.spp);
        const double jitter = toUnitFloat(hashCombine(mix64(s.seed), 0x5a77e4));
        std::vector<double> times;
        for (int k = 0; k < n; ++k) times.push_back(scene.shutter.frameTime(0, (k + jitter) / n));
        return times;
    }

    // Adds one of `passes` equally weighted pass images to the sum.
    static void accumulate(Image& sum, Image pass, std::size_t passes) {
        if (passes == 1) {
            sum = std::move(pass);
            return;
        }
        if (sum.data().empty()) sum = Image(pass.width(), pass.height(), pass.channelNames());
        const float w = 1.0f / float(passes);
        for (std::size_t i = 0; i < sum.data().size(); ++i) sum.data()[i] += w * pass.data()[i];
    }

    struct Surfaces {
        std::vector<SurfaceHit> hits;
        std::vector<double> tHit;  // distance to each hit, reference voxels (the pyramid's slices)
    };

    // Each padded level-0 pixel's first surface.
    static Surfaces traceSurfaces(const Scene& scene, const MeshAccel& accel, const Volume& vol, int pw, int ph, const RenderSettings& s) {
        Surfaces out{std::vector<SurfaceHit>(std::size_t(pw) * ph), std::vector<double>(std::size_t(pw) * ph)};
        tbb::parallel_for(0, ph, [&](int y) {
            for (int x = 0; x < pw; ++x) {
                const Ray ray = scene.camera.generate(x + 0.5, y + 0.5, s.width, s.height);
                const std::size_t i = std::size_t(y) * pw + x;
                out.hits[i] = firstSurface(accel, ray);
                out.tHit[i] = surfaceIndexDistance(vol, ray, out.hits[i]);
            }
        });
        return out;
    }

    static void shadeSurfaces(const Scene& scene, const MeshAccel& accel, const std::vector<SurfaceHit>& hits, int pw,
                              Image& image, RenderContext& ctx) {
        const RenderSettings& s = ctx.settings;
        scene.emitters();  // built before the pixel loop
        const float eps = rayEpsilon(scene);
        // The volume is one deterministic pass; --spp averages the surface's
        // light samples (stratified as the other techniques').
        const std::uint32_t spp = std::uint32_t(std::max(1, s.spp));
        // An image-space pass over the pixels' surface hits (the settings' row band).
        const int end = s.rowEnd < 0 ? s.height : std::min(s.rowEnd, s.height);
        tbb::parallel_for(std::clamp(s.rowBegin, 0, end), end, [&](int y) {
            SurfaceCounts counts;
            for (int x = 0; x < s.width; ++x) {
                const SurfaceHit& hit = hits[std::size_t(y) * pw + x];
                if (!hit.valid()) continue;
                const Ray ray = scene.camera.generate(x + 0.5, y + 0.5, s.width, s.height);
                Vec3f sum(0.0f);
                for (std::uint32_t k = 0; k < spp; ++k) {
                    ++counts.surface;
                    sum += shadeSurface(scene, accel, ray, hit, PixelSampler(s.seed, x, y, k, spp), eps, counts.shadow);
                }
                compositeBehind(image.pixel(x, y), sum / float(spp));
            }
            ctx.counters.add(kRaysSurface, counts.surface);
            ctx.counters.add(kRaysShadow, counts.shadow);
        });
    }

    // Figure 4 for slice i: levels l_slice down to 0, tiles of a level in
    // parallel. Off the full slices a pixel does work only when it is due,
    // so tiles with nothing due are passed over whole; on full slices,
    // quiet tiles with quiet parents (SliceWorker::staysQuiet) are too.
    void projectSlice(Pyramid& pyramid, SliceWorkers& workers, int i) const {
        const int lslice = sliceLevel(i, params_.lmax);
        const bool fullSlice = lslice == params_.lmax;
        for (int l = lslice; l >= 0; --l) {
            PyramidLevel& level = pyramid.level(l);
            tbb::parallel_for(tbb::blocked_range<int>(0, level.tilesY), [&](const tbb::blocked_range<int>& r) {
                SliceWorker& worker = workers.local();
                for (int ty = r.begin(); ty != r.end(); ++ty)
                    for (int tx = 0; tx < level.tilesX; ++tx) {
                        std::uint8_t& due = level.tileDueLevel[std::size_t(ty) * level.tilesX + tx];
                        if (fullSlice || due <= lslice) due = worker.tile(pyramid, l, lslice, i, tx, ty);
                    }
            });
        }
    }

    AdaptiveParams params_;
    const OracleInfo& oracle_;
};

}  // namespace

std::vector<ParamSpec> adaptiveParamSpecs() {
    std::vector<ParamSpec> specs = sliceParamSpecs();
    specs.push_back(stringParam("oracle", "gradient_alpha", "sampling-distance oracle (oracles: weft help volume.adaptive3d)",
                                [](const std::string& name) { oracles().get(name); }));
    specs.push_back(intParam("lmax", 3, 0, 6, "levels of skipping: distances up to 2^lmax slices (the paper uses 3)"));
    specs.push_back(floatParam("epsilon", 0.01, 0, 1, "oracle feature threshold: gradient_alpha |grad opacity| per voxel, majorant opacity change in a brick"));
    return specs;
}

namespace {

const TechniqueRegistrar registrar{{
    "volume.adaptive3d",
    "oracle-driven adaptive sampling along rays and in the image plane (Kraus et al. 2007)",
    ParamTable("volume.adaptive3d", adaptiveParamSpecs()),
    [](const Scene& scene, const ParamSet& p) { return std::make_unique<Adaptive3d>(scene, p); },
    /*motionBlur=*/false,
    /*renders=*/Content::VolumesAndMeshes,
    /*bytesPerPixel=*/140,  // pyramid levels of rays, values and distances (135 measured)
    /*reference=*/{"volume.raymarch", {"step=0.1"}, 256},
    /*knobs=*/{{"lmax", {"3", "2", "1", "0"}}, {"spacing", {"2", "1", "0.5"}}, {"spp", {"1", "4", "16", "64"}}},
    /*scatters=*/false,
    /*velocityBlur=*/true,
    /*emission=*/true,
}};

}  // namespace

}  // namespace weft
