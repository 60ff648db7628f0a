// analytic.2d — analytic test images with exact references (core/sampling/analytic2d.hpp).
//
// Renders a 2D scene through the image-plane sampler every camera-ray
// technique uses (core/sampling/image_plane.hpp): supersampling with any
// pattern set, reconstruction filters, adaptive supersampling and adaptive
// stochastic sampling, and motion blur from each sample's time coordinate
// (interleaved sets give interleaved time samples, Keller & Heidrich 4.2).
// With reference=true every pixel is the exact box-filtered integral
// (time-averaged for the moving disc), whatever the sampling settings.
//
// Inputs: builtin:zoneplate, builtin:grating, builtin:checker, builtin:siemens, builtin:lines,
// builtin:disc (or any input with --technique analytic.2d --set scene=NAME).
// Counters: image.samples (point evaluations; with reference=true, pixel integrals).
#include "core/sampling/analytic2d.hpp"
#include "core/sampling/image_plane.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

std::vector<ParamSpec> analyticParams() {
    std::vector<ParamSpec> specs = {
        enumParam("scene", "zoneplate", {"zoneplate", "grating", "checker", "siemens", "lines", "disc"}, "which analytic image"),
        boolParam("reference", false, "exact pixel integrals (box filter, whole shutter) instead of sampling"),
    };
    return withImagePlaneParams(std::move(specs));
}

class Analytic2D final : public Technique {
public:
    explicit Analytic2D(const ParamSet& p)
        : scene_(analyticSceneFromName(p.getString("scene"))), reference_(p.getBool("reference")),
          plane_(readImagePlaneOptions(p)) {}

    Image render(const Scene&, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        const AnalyticImage image(scene_, s.width, s.height);
        if (reference_) return exact(image, ctx);
        const ImagePlane plane(plane_, s);
        struct Shader {
            const AnalyticImage& image;
            Rgba operator()(const CameraSample& c) const {
                const float v = float(image.value(c.x, c.y, c.time));
                return {v, v, v, 1.0f};
            }
            void flush(Counters&) const {}
        };
        return plane.render(ctx, "analytic.2d", [&] { return Shader{image}; });
    }

private:
    // One camera sample per pixel through the plane; the shader returns the
    // pixel's exact integral wherever the sample lies.
    static Image exact(const AnalyticImage& image, RenderContext& ctx) {
        RenderSettings single = ctx.settings;
        single.spp = 1;
        struct Exact {
            const AnalyticImage& image;
            Rgba operator()(const CameraSample& c) const {
                const float v = float(image.pixelIntegral(c.px, c.py));
                return {v, v, v, 1.0f};
            }
            void flush(Counters&) const {}
        };
        return ImagePlane(ImagePlaneOptions{}, single).render(ctx, "analytic.2d reference", [&] { return Exact{image}; });
    }

    AnalyticScene scene_;
    bool reference_;
    ImagePlaneOptions plane_;
};

const TechniqueRegistrar registrar{{
    "analytic.2d",
    "analytic test images (zone plate, grating, checkerboard, Siemens star, thin lines, moving disc) with exact references",
    ParamTable("analytic.2d", analyticParams()),
    [](const Scene&, const ParamSet& p) { return std::make_unique<Analytic2D>(p); },
    /*motionBlur=*/false,
    /*renders=*/Content::None,
    /*bytesPerPixel=*/32,
    /*reference=*/{"analytic.2d", {"reference=true"}, 1},
    /*knobs=*/{{"spp", {"1", "4", "16", "64"}}},
}};

}  // namespace

}  // namespace weft
