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
// Counters: image.samples (point evaluations).
#include "core/sampling/analytic2d.hpp"
#include "core/sampling/pixel_loop.hpp"
#include "core/sampling/image_plane.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

std::vector<ParamSpec> analyticParams() {
    std::vector<ParamSpec> specs = {
        enumParam("scene", "zoneplate", {"zoneplate", "grating", "checker", "siemens", "lines", "disc"}, "which analytic image"),
        boolParam("reference", false, "exact pixel integrals (box filter, whole shutter) instead of sampling"),
    };
    for (ParamSpec& s : imagePlaneParamSpecs()) specs.push_back(std::move(s));
    return specs;
}

class Analytic2D final : public Technique {
public:
    explicit Analytic2D(const ParamSet& p)
        : scene_(analyticSceneFromName(p.getString("scene"))), reference_(p.getBool("reference")),
          plane_(readImagePlaneOptions(p)) {}

    Image render(const Scene&, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        const AnalyticImage image(scene_, s.width, s.height);
        if (reference_) return exact(image, s);
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
    static Image exact(const AnalyticImage& image, const RenderSettings& s) {
        Image out = Image::rgba(s.width, s.height);
        forEachRow(s, "analytic.2d reference", [&](int y) {
            for (int x = 0; x < s.width; ++x) {
                const float v = float(image.pixelIntegral(x, y));
                float* px = out.pixel(x, y);
                px[0] = px[1] = px[2] = v, px[3] = 1.0f;
            }
        });
        return out;
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
}};

}  // namespace

}  // namespace weft
