#include "core/color.hpp"

#include <OpenColorIO/OpenColorIO.h>

#include <cstdlib>
#include <mutex>

#include "core/error.hpp"

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

    config->setRole(OCIO::ROLE_SCENE_LINEAR, "lin_rec709");
    config->setRole(OCIO::ROLE_DEFAULT, "lin_rec709");
    config->addDisplayView("sRGB", "Standard", "srgb_display", "");
    config->setActiveDisplays("sRGB");
    config->setActiveViews("Standard");
    config->validate();
    return config;
}

class OcioDisplayTransform final : public DisplayTransform {
public:
    OcioDisplayTransform() {
        const char* env = std::getenv("OCIO");
        try {
            config_ = (env && *env) ? OCIO::Config::CreateFromEnv() : builtinConfig();
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

}  // namespace

const DisplayTransform& displayTransform() {
    static std::once_flag once;
    static std::unique_ptr<DisplayTransform> instance;
    std::call_once(once, [] { instance = std::make_unique<OcioDisplayTransform>(); });
    return *instance;
}

}  // namespace weft
