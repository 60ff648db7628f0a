// volume.adaptive3d — oracle-based adaptive sampling in three dimensions
// (Kraus, Strengert, Klein, Ertl 2007).
//
// An oracle (oracles/) gives a sampling distance d everywhere. Slices are
// processed front to back (core/volume/slices.hpp); slice i starts at pyramid level
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
// weights (core/volume/preintegration.hpp), as in volume.preint; they are
// built only when a volume emits. The oracles see emission as a feature
// where one slice's emitted radiance changes by more than epsilon per voxel
// (oracles/feature_distance.hpp), so a glowing region is never skipped as
// if empty; the oracle cache keys an emitting volume by its emission too.
// Velocity (moving volumes) is not rendered.
//
// Meshes: each pixel's ray ends at its first surface (Embree, built only
// when the scene has meshes). Skipping never passes it (SliceWorker::
// surfaceBound): a pixel composites on its last slice in front of the
// surface, then the cut segment with its true length, exactly as
// volume.preint does; coarse pixels stop at the nearest surface of their
// footprint and are refined where its surfaces differ in depth. The
// surface is shaded and composited behind (core/lighting/surface_shading.hpp)
// with --spp light samples at the pixel centre (the volume pass is one).
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

#include "core/base/progress.hpp"
#include "core/lighting/delta_lights.hpp"
#include "core/lighting/surface_shading.hpp"
#include "core/volume/segment_tables.hpp"
#include "core/volume/slices.hpp"
#include "oracles/oracle_cache.hpp"
#include "core/volume/slice_renderer.hpp"
#include "plugins/technique.hpp"
#include "plugins/volume_adaptive3d/pyramid.hpp"

namespace weft {

namespace {

const Counter kPreintegrationTables{"preintegration.tables", "pre-integration tables built"};
const Counter kOracleBuilt{"oracle.built", "oracle fields built by this render (one per volume)"};
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
        std::vector<OracleField> fields;
        {
            ScopedTimer timer(ctx.timings, "oracle");
            for (const SliceVolume& v : volumes) {
                SharedOracleField shared =
                    sharedOracleField(oracle_, {*v.volume, params_.slice.spacing * v.lengthScale, params_.lmax, params_.epsilon});
                ctx.counters.add(shared.reused ? kOracleReused : kOracleBuilt, 1);
                fields.push_back(std::move(shared.field));
            }
        }
        Pyramid pyramid(scene.camera, volumes, slices, params_.lmax, pw, ph, s.width, s.height);
        const MeshAccel* accel = scene.meshes.empty() ? nullptr : &scene.accel();  // no BVH without meshes
        std::vector<SurfaceHit> hits;
        if (accel) hits = traceSurfaces(scene, *accel, vol, pyramid, slices, pw, ph, s);
        SliceTables tables(volumes, params_.slice.spacing, block, params_.slice.tableResolution, params_.slice.precision);
        SliceContext sc{volumes, fields, slices, tables, params_.lmax, ctx.counters};
        Progress progress("volume.adaptive3d", slices.imax + 1, s.showProgress);
        for (int i = 0; i <= slices.imax; ++i) {
            projectSlice(pyramid, sc, i);
            progress.advance();
        }
        progress.finish();
        ctx.counters.add(kSlices, slices.imax + 1);
        ctx.counters.add(kPreintegrationTables, tables.builtCount());
        if (const int n = tables.emissionBuiltCount()) ctx.counters.add(kEmissionTables, n);
        Image image = pyramid.image(s.width, s.height);
        if (accel) shadeSurfaces(scene, *accel, hits, pw, image, ctx);
        return image;
    }

private:
    // Each padded level-0 pixel's first surface; their slices go to the pyramid.
    static std::vector<SurfaceHit> traceSurfaces(const Scene& scene, const MeshAccel& accel, const Volume& vol, Pyramid& pyramid,
                                                 const SliceSetup& slices, int pw, int ph, const RenderSettings& s) {
        std::vector<SurfaceHit> hits(std::size_t(pw) * ph);
        std::vector<double> tHit(hits.size());
        tbb::parallel_for(0, ph, [&](int y) {
            for (int x = 0; x < pw; ++x) {
                const Ray ray = scene.camera.generate(x + 0.5, y + 0.5, s.width, s.height);
                const std::size_t i = std::size_t(y) * pw + x;
                hits[i] = firstSurface(accel, ray);
                tHit[i] = surfaceIndexDistance(vol, ray, hits[i]);
            }
        });
        pyramid.setSurfaces(std::move(tHit), slices);
        return hits;
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
    // so tiles with nothing due are passed over whole.
    void projectSlice(Pyramid& pyramid, SliceContext& sc, int i) const {
        const int lslice = sliceLevel(i, params_.lmax);
        const bool fullSlice = lslice == params_.lmax;
        for (int l = lslice; l >= 0; --l) {
            PyramidLevel& level = pyramid.level(l);
            tbb::parallel_for(tbb::blocked_range<int>(0, level.tilesY), [&](const tbb::blocked_range<int>& r) {
                SliceWorker worker(sc);
                for (int ty = r.begin(); ty != r.end(); ++ty)
                    for (int tx = 0; tx < level.tilesX; ++tx) {
                        std::uint8_t& due = level.tileDueLevel[std::size_t(ty) * level.tilesX + tx];
                        if (fullSlice || due <= lslice) due = worker.tile(pyramid, l, lslice, i, tx, ty);
                    }
                worker.flush();
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
}};

}  // namespace

}  // namespace weft
