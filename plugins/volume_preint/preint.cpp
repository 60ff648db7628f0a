// volume.preint — fixed-rate slice renderer with pre-integrated segments.
//
// Every ray is sampled on every slice (shells t_i = tNear + i * spacing, see
// core/slices.hpp) and each segment between neighbouring slices is
// composited from a pre-integration table lookup (s_front, s_back, one
// slice). This is the "tex.-based" column of Kraus et al. 2007, Tables 2-3:
// the reference volume.adaptive3d is measured against at the same spacing.
//
// Counters: rays.camera, slices, volume.samples (one trilinear lookup per
// slice inside the volume: the back sample of one segment is the front
// sample of the next), composite.ops.
#include "core/pixel_loop.hpp"
#include "core/segment_tables.hpp"
#include "core/slices.hpp"
#include "plugins/slice_renderer.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

class Preint final : public Technique {
public:
    Preint(const Scene& scene, const ParamSet& p) : params_(readSliceParams(p)) {
        requireSliceableVolume(scene, "volume.preint");
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        const Volume& vol = scene.volumes.front();
        const SliceSetup slices = makeSliceSetup(scene.camera, vol, params_.spacing, 0);
        const LevelRays rays = makeLevelRays(scene.camera, vol, slices, 0, s.width, s.height, s.width, s.height);
        SegmentTables tables(vol.tf, params_.spacing, 1, params_.tableResolution, params_.precision);
        const PreintegrationTable& table = tables.forSlices(1);
        Image image = Image::rgba(s.width, s.height);
        forEachRow(s, "volume.preint", [&](int y) {
            ScalarSampler sampler(vol);
            std::int64_t samples = 0, composites = 0;
            for (int x = 0; x < s.width; ++x) {
                const int i = rays.index(x, y);
                SegmentCompositor acc;
                // Segments wholly outside the volume are transparent: start one slice before it.
                const int from = std::max(rays.first[i] - 1, 0), to = std::min(rays.last[i] + 1, slices.imax);
                auto scalarAt = [&](int k) {
                    const bool inside = k >= rays.first[i] && k <= rays.last[i];
                    samples += inside;
                    return inside ? sampler.sample(slices.eye + rays.dir[i] * slices.t(k)) : sampler.background();
                };
                float prev = scalarAt(from);
                for (int k = from + 1; k <= to; ++k) {
                    const float cur = scalarAt(k);
                    acc.add(table.lookup(0, prev, cur));
                    ++composites;
                    prev = cur;
                }
                float* px = image.pixel(x, y);
                px[0] = acc.r, px[1] = acc.g, px[2] = acc.b, px[3] = acc.a;
            }
            ctx.counters.add("volume.samples", samples);
            ctx.counters.add("composite.ops", composites);
            ctx.counters.add("rays.camera", s.width);
        });
        ctx.counters.add("slices", slices.imax + 1);
        return image;
    }

private:
    SliceParams params_;
};

const TechniqueRegistrar registrar{{
    "volume.preint",
    "fixed-rate slices with pre-integrated segments (Kraus et al. 2007, the tex.-based reference)",
    ParamTable("volume.preint", sliceParamSpecs()),
    [](const Scene& scene, const ParamSet& p) { return std::make_unique<Preint>(scene, p); },
}};

}  // namespace

}  // namespace weft
