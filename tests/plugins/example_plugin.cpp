// A minimal external plugin, built as example.weft.so: it registers
// "example.gradient", which fills the image with a horizontal ramp whose
// brightness is its one parameter.
#include "core/base/options/params.hpp"
#include "plugins/plugin_api.hpp"

namespace {

const weft::Counter kExamplePixels{"example.pixels", "pixels the example plugin wrote"};

class Gradient final : public weft::Technique {
public:
    explicit Gradient(double gain) : gain_(gain) {}
    weft::Image render(const weft::Scene&, weft::RenderContext& ctx) override {
        weft::Image img = weft::Image::rgba(ctx.settings.width, ctx.settings.height);
        for (int y = 0; y < img.height(); ++y)
            for (int x = 0; x < img.width(); ++x) {
                const float v = float(gain_ * (x + 0.5) / img.width());
                img.at(x, y, 0) = img.at(x, y, 1) = img.at(x, y, 2) = v;
                img.at(x, y, 3) = 1.0f;
            }
        ctx.counters.add(kExamplePixels, std::int64_t(img.width()) * img.height());
        return img;
    }

private:
    double gain_;
};

}  // namespace

extern "C" int weft_plugin_abi_version() { return WEFT_PLUGIN_ABI_VERSION; }

extern "C" void weft_plugin_register(weft::TechniqueRegistry* registry) {
    registry->add({"example.gradient", "an external plugin: a horizontal ramp",
                   weft::ParamTable("example.gradient", {weft::floatParam("gain", 1.0, 0.0, 10.0, "brightness at the right edge")}),
                   [](const weft::Scene&, const weft::ParamSet& p) { return std::make_unique<Gradient>(p.getFloat("gain")); }});
}
