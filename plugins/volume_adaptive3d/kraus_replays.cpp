// kraus.fig4 and kraus.fig9 — the two GPU variants of volume.adaptive3d
// (Kraus et al. 2007, Sec. 3.4) as pass lists through hwsim, driven by the
// same scene, oracle, pyramid and per-pixel operations (SliceWorker) as the
// core renderer, so the image and volume.samples equal the core's exactly.
// Each pyramid level is a render target of its own, drawn as one
// screen-aligned rectangle per pass.
//
// fig4 (Sec. 3.4.1, pixel-depth tests): the depth buffer of level l holds
// d / 2^lmax (exact: a power-of-two scale) and the conditions on d are depth
// bounds tests; a strict "d < 2^k" is the inclusive bound nextafter(2^k, 0).
// Per level, from l_slice down to 0:
//   synthesize   l < l_slice, bounds d < 2^(l_slice+1) (none when l_slice = lmax)
//   sample       l > 0, bounds d < 2^(l+1) (none on lmax); writes the new d
//   accumulate   l = 0, bounds 2 <= d < 2^(l_slice+1): composite unsampled pixels
//   sample+acc.  l = 0, bounds d < 2: sample, then composite
// (accumulate runs before sample+accumulate so that decisions use the d held
// before this slice's sample, as the core does). The bounds change from pass
// to pass — what lost the paper's hardware its early test.
//
// fig9 (Sec. 3.4.2, early fragment-depth tests, depth function LESS): three
// depth values per slice, 0, 2, 4 + 6 (imax - i), so every value written on
// slice i is below those of earlier slices. Per level:
//   write z      every pixel (it writes depth): synthesize where due (the
//                core's condition; the paper's figure synthesizes every pixel),
//                then z = 4 (sample), 2 (only accumulate) or 0 (neither)
//   sample       drawn at 3 + 6 (imax - i): passes where z = 4 (no test on lmax)
//   accumulate   l = 0, drawn at 1 + 6 (imax - i): z = 2 or 4 (no test when l_slice = lmax)

#include <cmath>
#include <memory>

#include "core/base/error.hpp"
#include "hwsim/pipeline.hpp"
#include "hwsim/replay.hpp"
#include "core/volume/slice/slice_renderer.hpp"
#include "plugins/volume_adaptive3d/pyramid.hpp"

namespace weft {

namespace {

using namespace hwsim;

// The core renderer's state for one render, built as Adaptive3d::render builds it.
struct KrausState {
    KrausState(const Scene& s, const ParamSet& p, int width, int height)
        : scene(s), vol(oneVolume(scene)), volumes(makeSliceVolumes(scene.volumes)), slice(readSliceParams(p)),
          lmax(int(p.getInt("lmax"))), block(1 << lmax),
          slices(makeSliceSetup(scene.camera, vol, slice.spacing, lmax)),
          fields{oracles().get(p.getString("oracle")).build({vol, slice.spacing, lmax, p.getFloat("epsilon")})},
          pyramid(scene.camera, volumes, slices, lmax, (width + block - 1) / block * block,
                  (height + block - 1) / block * block, width, height),
          tables(volumes, slice.spacing, block, slice.tableResolution, slice.precision),
          sc{volumes, fields, slices, tables, lmax, counters} {}

    // The replays draw the paper's passes for one volume and no meshes.
    static const Volume& oneVolume(const Scene& scene) {
        const Volume& v = requireSliceableVolume(scene, "kraus replay");
        if (scene.volumes.size() != 1 || !scene.meshes.empty())
            throw Error("kraus replay renders exactly one volume and no meshes; the scene has " + std::to_string(scene.volumes.size()) +
                        " volumes and " + std::to_string(scene.meshes.size()) + " meshes");
        return v;
    }

    SliceWorker& worker() { return workers.local(); }
    CounterMap finish() {
        workers.flush();
        counters.add(kSlices, slices.imax + 1);
        return counters.merged();
    }

    const Scene& scene;
    const Volume& vol;
    std::vector<SliceVolume> volumes;
    SliceParams slice;
    int lmax, block;
    SliceSetup slices;
    std::vector<OracleField> fields;
    Pyramid pyramid;
    SliceTables tables;
    Counters counters;
    SliceContext sc;
    SliceWorkers workers{sc};
};

// One render target per level, sized like the level's image.
struct LevelTargets {
    LevelTargets(KrausState& k, const Profile& profile, float clearDepth) {
        for (int l = 0; l <= k.lmax; ++l) {
            const LevelRays& r = k.pyramid.level(l).rays;
            fbs.push_back(std::make_unique<Framebuffer>(r.width, r.height, clearDepth));
            pipes.push_back(std::make_unique<Pipeline>(*fbs.back(), profile));
        }
    }
    StageCounts total() const {
        StageCounts c;
        for (const auto& p : pipes) c.add(p->counts());
        return c;
    }
    std::vector<std::unique_ptr<Framebuffer>> fbs;
    std::vector<std::unique_ptr<Pipeline>> pipes;
};

float below(float v) { return std::nextafter(v, 0.0f); }

void setBounds(Pipeline& pipe, bool on, float lo, float hi) { pipe.state.bounds = {on, lo, hi}; }

// A program that only costs its run; its work is done where a GPU writes
// the program's outputs (withWrites), so late-rejected fragments change nothing.
const auto kRuns = [](const Fragment&, FragmentOutput&) {};

// Figure 4 on slice i with pixel-depth (bounds) tests. The passes that
// update d write it as depth with ALWAYS; the write is the program's output,
// stored with the other outputs (the depth test itself is off: ALWAYS
// never rejects).
void fig4Slice(KrausState& k, LevelTargets& t, int i) {
    const int lslice = sliceLevel(i, k.lmax);
    const float scale = 1.0f / float(k.block);  // depth = d / 2^lmax
    const ProgramTraits writesD{.writesDepth = true};
    for (int l = lslice; l >= 0; --l) {
        PyramidLevel& level = k.pyramid.level(l);
        Pipeline& pipe = *t.pipes[l];
        Framebuffer& fb = *t.fbs[l];
        const int w = level.rays.width, h = level.rays.height;
        auto storeD = [&](const Fragment& f, int idx) { fb.depth[fb.index(f.x, f.y)] = level.d[idx] * scale; };
        auto synthesize = [&](const Fragment& f, const FragmentOutput&) {
            const int idx = level.rays.index(f.x, f.y);
            k.worker().synthesize(k.pyramid, l, f.x, f.y, idx, i);
            storeD(f, idx);
        };
        auto sample = [&](const Fragment& f, const FragmentOutput&) {
            const int idx = level.rays.index(f.x, f.y);
            k.worker().sample(k.pyramid, l, idx, i);
            storeD(f, idx);
        };
        auto composite = [&](const Fragment& f, const FragmentOutput&) {
            k.worker().composite(k.pyramid, level.rays.index(f.x, f.y), i);
        };
        if (l < lslice) {
            setBounds(pipe, lslice != k.lmax, 0, below(float(2 << lslice)) * scale);
            pipe.drawRect(0, 0, w, h, 0, withWrites(kRuns, synthesize), writesD);
        }
        if (l > 0) {
            setBounds(pipe, l != k.lmax, 0, below(float(2 << l)) * scale);
            pipe.drawRect(0, 0, w, h, 0, withWrites(kRuns, sample), writesD);
            continue;
        }
        if (k.lmax > 0) {
            setBounds(pipe, true, 2 * scale, lslice == k.lmax ? 1.0f : below(float(2 << lslice)) * scale);
            pipe.drawRect(0, 0, w, h, 0, withWrites(kRuns, composite));
        }
        setBounds(pipe, k.lmax > 0, 0, below(2.0f) * scale);
        auto sampleAndComposite = [&](const Fragment& f, const FragmentOutput& o) { sample(f, o), composite(f, o); };
        pipe.drawRect(0, 0, w, h, 0, withWrites(kRuns, sampleAndComposite), writesD);
    }
}

// Figure 9 on slice i with early fragment-depth tests (LESS, decreasing
// values). The first pass writes depth for every pixel, and its depth always
// passes LESS (it is below every value of earlier slices), so it is stored
// with the program's other outputs.
void fig9Slice(KrausState& k, LevelTargets& t, int i) {
    const int lslice = sliceLevel(i, k.lmax);
    const float base = 6.0f * float(k.slices.imax - i), range = 6.0f * float(k.slices.imax + 1);
    auto z = [&](float v) { return (v + base) / range; };
    for (int l = lslice; l >= 0; --l) {
        PyramidLevel& level = k.pyramid.level(l);
        Pipeline& pipe = *t.pipes[l];
        Framebuffer& fb = *t.fbs[l];
        const int w = level.rays.width, h = level.rays.height;
        auto writeZ = [&](const Fragment& f, const FragmentOutput&) {
            const int idx = level.rays.index(f.x, f.y);
            if (l < lslice && isDue(level.d[idx], lslice, k.lmax)) k.worker().synthesize(k.pyramid, l, f.x, f.y, idx, i);
            const float d = level.d[idx];
            fb.depth[fb.index(f.x, f.y)] = z(l == k.lmax || d < float(2 << l) ? 4.0f : isDue(d, lslice, k.lmax) ? 2.0f : 0.0f);
        };
        pipe.state.depth = {false, CompareFunc::Less, true};
        pipe.drawRect(0, 0, w, h, 0, withWrites(kRuns, writeZ), {.writesDepth = true});
        auto sample = [&](const Fragment& f, const FragmentOutput&) { k.worker().sample(k.pyramid, l, level.rays.index(f.x, f.y), i); };
        pipe.state.depth = {l != k.lmax, CompareFunc::Less, false};
        pipe.drawRect(0, 0, w, h, z(3), withWrites(kRuns, sample));
        if (l > 0) continue;
        auto composite = [&](const Fragment& f, const FragmentOutput&) { k.worker().composite(k.pyramid, level.rays.index(f.x, f.y), i); };
        pipe.state.depth = {lslice != k.lmax, CompareFunc::Less, false};
        pipe.drawRect(0, 0, w, h, z(1), withWrites(kRuns, composite));
    }
}

using SliceFn = void (*)(KrausState&, LevelTargets&, int);

ReplayResult runKraus(const Profile& profile, const ParamSet& p, const char* label, SliceFn slice, float clearDepth) {
    const int w = int(p.getInt("width")), h = int(p.getInt("height"));
    const Scene scene = loadScene(p.getString("scene"), double(w) / h);
    KrausState k(scene, p, w, h);
    LevelTargets targets(k, profile, clearDepth < 0 ? 1.0f / float(k.block) : clearDepth);
    for (int i = 0; i <= k.slices.imax; ++i) slice(k, targets, i);
    ReplayResult result;
    result.variants.push_back({label, withStageCounts(targets.total(), k.finish())});
    result.image = k.pyramid.image(w, h);
    return result;
}

std::vector<ParamSpec> krausParamSpecs() {
    std::vector<ParamSpec> specs = {stringParam("scene", "builtin:cloud", "scene: .json, .vdb or builtin:NAME (as weft render)"),
                                    intParam("width", 128, 1, 8192, "image width (pixels)"),
                                    intParam("height", 128, 1, 8192, "image height (pixels)")};
    for (ParamSpec& s : adaptiveParamSpecs()) specs.push_back(std::move(s));
    return specs;
}

const ReplayRegistrar fig4{{
    "kraus.fig4",
    "Kraus et al. 2007 Fig. 4 on a GPU with depth bounds tests (Sec. 3.4.1); image and samples equal volume.adaptive3d",
    ParamTable("kraus.fig4", krausParamSpecs()),
    [](const Profile& profile, const ParamSet& p) {
        profile.require(profile.bounds != BoundsSupport::Unsupported, "the depth bounds test (EXT_depth_bounds_test)", "kraus.fig4");
        return runKraus(profile, p, "fig4", fig4Slice, -1);
    },
}};

const ReplayRegistrar fig9{{
    "kraus.fig9",
    "Kraus et al. 2007 Fig. 9 with early fragment-depth tests (Sec. 3.4.2); image and samples equal volume.adaptive3d",
    ParamTable("kraus.fig9", krausParamSpecs()),
    [](const Profile& profile, const ParamSet& p) { return runKraus(profile, p, "fig9", fig9Slice, 1.0f); },
}};

}  // namespace

}  // namespace weft
