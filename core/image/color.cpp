#include "core/image/color.hpp"

#include <OpenColorIO/OpenColorIO.h>

#include <cmath>
#include <cstdlib>
#include <vector>
#include <mutex>

#include "core/base/error.hpp"
#include "core/image/image.hpp"

namespace OCIO = OCIO_NAMESPACE;

namespace weft {

namespace {

// OCIO 2.1 has no built-in configs, so the default one is built here:
// a scene-linear Rec.709 reference space and the sRGB display encoding.
OCIO::ConstConfigRcPtr builtinConfig() {
    OCIO::ConfigRcPtr config = OCIO::Config::Create();
    config->setName("weft-builtin");

    OCIO::ColorSpaceRcPtr linear = OCIO::ColorSpace::Create();
    linear->setName("lin_rec709");
    linear->setFamily("scene-linear");
    config->addColorSpace(linear);

    OCIO::ColorSpaceRcPtr srgb = OCIO::ColorSpace::Create();
    srgb->setName("srgb_display");
    srgb->setFamily("display");
    auto curve = OCIO::ExponentWithLinearTransform::Create();
    curve->setGamma({2.4, 2.4, 2.4, 1.0});
    curve->setOffset({0.055, 0.055, 0.055, 0.0});
    curve->setDirection(OCIO::TRANSFORM_DIR_INVERSE);  // linear -> encoded
    srgb->setTransform(curve, OCIO::COLORSPACE_DIR_FROM_REFERENCE);
    config->addColorSpace(srgb);

    // ACEScg: linear, AP1 primaries, D60 white; from Rec.709 (D65) with the
    // Bradford-adapted matrix of the ACES documentation (rows sum to 1, so
    // neutral stays neutral).
    OCIO::ColorSpaceRcPtr acescg = OCIO::ColorSpace::Create();
    acescg->setName("acescg");
    acescg->setFamily("scene-linear");
    auto toAp1 = OCIO::MatrixTransform::Create();
    const double m[16] = {0.6130974024, 0.3395231462, 0.0473794514, 0, 0.0701937225, 0.9163538791, 0.0134523985, 0,
                          0.0206155929, 0.1095697729, 0.8698146342, 0, 0, 0, 0, 1};
    toAp1->setMatrix(m);
    acescg->setTransform(toAp1, OCIO::COLORSPACE_DIR_FROM_REFERENCE);
    config->addColorSpace(acescg);

    config->setRole(OCIO::ROLE_SCENE_LINEAR, "lin_rec709");
    config->setRole(OCIO::ROLE_DEFAULT, "lin_rec709");
    config->addDisplayView("sRGB", "Standard", "srgb_display", "");
    config->setActiveDisplays("sRGB");
    config->setActiveViews("Standard");
    config->validate();
    return config;
}

// $OCIO's config, else the built-in one; built once.
OCIO::ConstConfigRcPtr activeConfig() {
    static std::once_flag once;
    static OCIO::ConstConfigRcPtr config;
    static std::string error;
    std::call_once(once, [] {
        const char* env = std::getenv("OCIO");
        try {
            config = (env && *env) ? OCIO::Config::CreateFromEnv() : builtinConfig();
        } catch (const OCIO::Exception& e) {
            error = std::string("colour management: ") + (env ? "$OCIO config '" + std::string(env) + "': " : "") + e.what();
        }
    });
    if (!config) throw Error(error);
    return config;
}

class OcioDisplayTransform final : public DisplayTransform {
public:
    OcioDisplayTransform() {
        const char* env = std::getenv("OCIO");
        config_ = activeConfig();
        try {
            const char* display = config_->getDefaultDisplay();
            const char* view = config_->getDefaultView(display);
            auto transform = OCIO::DisplayViewTransform::Create();
            transform->setSrc(OCIO::ROLE_SCENE_LINEAR);
            transform->setDisplay(display);
            transform->setView(view);
            cpu_ = config_->getProcessor(transform)->getDefaultCPUProcessor();
            description_ = std::string(config_->getName()) + ": " + display + " / " + view;
        } catch (const OCIO::Exception& e) {
            throw Error(std::string("colour management: ") + (env ? "$OCIO config '" + std::string(env) + "': " : "") +
                        e.what());
        }
    }
    void apply(float* rgb, int count) const override {
        OCIO::PackedImageDesc desc(rgb, count, 1, 3);
        cpu_->apply(desc);
    }
    std::string description() const override { return description_; }

private:
    OCIO::ConstConfigRcPtr config_;
    OCIO::ConstCPUProcessorRcPtr cpu_;
    std::string description_;
};

class OcioColorConversion final : public ColorConversion {
public:
    explicit OcioColorConversion(OCIO::ConstCPUProcessorRcPtr cpu) : cpu_(std::move(cpu)) {}

    void apply(Image& image) const override {
        const int r = image.channelIndex("R"), g = image.channelIndex("G"), b = image.channelIndex("B"), a = image.channelIndex("A");
        if (r < 0 || g < 0 || b < 0) throw Error("colorconvert: the image has no R, G, B channels");
        std::vector<float> row(3 * std::size_t(image.width()));
        for (int y = 0; y < image.height(); ++y) {
            for (int x = 0; x < image.width(); ++x) {
                const float alpha = a >= 0 ? image.at(x, y, a) : 1.0f;
                const float unpremult = alpha > 0.0f && alpha < 1.0f ? 1.0f / alpha : 1.0f;
                for (int c = 0; c < 3; ++c) row[3 * std::size_t(x) + c] = image.at(x, y, c == 0 ? r : c == 1 ? g : b) * unpremult;
            }
            OCIO::PackedImageDesc desc(row.data(), image.width(), 1, 3);
            cpu_->apply(desc);
            for (int x = 0; x < image.width(); ++x) {
                const float alpha = a >= 0 ? image.at(x, y, a) : 1.0f;
                const float premult = alpha > 0.0f && alpha < 1.0f ? alpha : 1.0f;
                for (int c = 0; c < 3; ++c) {
                    const float v = row[3 * std::size_t(x) + c] * premult;
                    image.at(x, y, c == 0 ? r : c == 1 ? g : b) = std::isfinite(v) ? v : 0.0f;
                }
            }
        }
    }

private:
    OCIO::ConstCPUProcessorRcPtr cpu_;
};

}  // namespace

std::unique_ptr<ColorConversion> colorConversion(const std::string& from, const std::string& to) {
    const OCIO::ConstConfigRcPtr config = activeConfig();
    for (const std::string* name : {&from, &to})
        if (!config->getColorSpace(name->c_str())) {
            std::string known;
            for (int i = 0; i < config->getNumColorSpaces(); ++i)
                known += std::string(known.empty() ? "" : ", ") + config->getColorSpaceNameByIndex(i);
            throw Error("colorconvert: unknown colour space '" + *name + "' in config '" + config->getName() + "' (" + known + ")");
        }
    try {
        return std::make_unique<OcioColorConversion>(config->getProcessor(from.c_str(), to.c_str())->getDefaultCPUProcessor());
    } catch (const OCIO::Exception& e) {
        throw Error("colorconvert " + from + " " + to + ": " + e.what());
    }
}

const DisplayTransform& displayTransform() {
    static std::once_flag once;
    static std::unique_ptr<DisplayTransform> instance;
    std::call_once(once, [] { instance = std::make_unique<OcioDisplayTransform>(); });
    return *instance;
}

}  // namespace weft
