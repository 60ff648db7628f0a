#include "core/image/color.hpp"

#include <OpenColorIO/OpenColorIO.h>

#include <openvdb/math/Mat3.h>

#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <vector>
#include <mutex>

#include "core/base/error.hpp"
#include "core/image/image.hpp"

namespace OCIO = OCIO_NAMESPACE;

namespace weft {

namespace {

// The 3x3 matrix from linear RGB of primaries (x, y) and white point (x, y)
// to CIE XYZ, as a row-major 4x4 for OCIO's MatrixTransform: the primaries'
// XYZ columns scaled so that RGB (1, 1, 1) maps to the white at Y = 1.
std::array<double, 16> rgbToXyz(const double (&primaries)[3][2], const double (&white)[2]) {
    const auto xyz = [](const double (&c)[2]) { return openvdb::math::Vec3d(c[0] / c[1], 1.0, (1.0 - c[0] - c[1]) / c[1]); };
    openvdb::math::Mat3d p;
    for (int i = 0; i < 3; ++i) p.setCol(i, xyz(primaries[i]));
    const openvdb::math::Vec3d scale = p.inverse() * xyz(white);
    std::array<double, 16> m{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m[4 * r + c] = p(r, c) * scale[c];
    m[15] = 1;
    return m;
}

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

    // CIE XYZ with the D65 white at Y = 1, for colours given as spectra
    // (blackbody emission); OCIO v2 configs name it by the role below.
    OCIO::ColorSpaceRcPtr xyz = OCIO::ColorSpace::Create();
    xyz->setName("cie_xyz_d65");
    xyz->setFamily("scene-linear");
    auto toXyz = OCIO::MatrixTransform::Create();
    const std::array<double, 16> rec709 = rgbToXyz({{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}}, {0.3127, 0.3290});
    toXyz->setMatrix(rec709.data());
    xyz->setTransform(toXyz, OCIO::COLORSPACE_DIR_FROM_REFERENCE);
    config->addColorSpace(xyz);

    config->setRole(OCIO::ROLE_SCENE_LINEAR, "lin_rec709");
    config->setRole(OCIO::ROLE_INTERCHANGE_DISPLAY, "cie_xyz_d65");
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
            cpu_ = config_->getProcessor(transform)->getOptimizedCPUProcessor(OCIO::BIT_DEPTH_F16, OCIO::BIT_DEPTH_UINT8,
                                                                                OCIO::OPTIMIZATION_DEFAULT);
            description_ = std::string(config_->getName()) + ": " + display + " / " + view;
        } catch (const OCIO::Exception& e) {
            throw Error(std::string("colour management: ") + (env ? "$OCIO config '" + std::string(env) + "': " : "") +
                        e.what());
        }
    }
    void encode8(const float* rgb, unsigned char* out, int count) const override {
        constexpr float kHalfMax = 65504.0f;  // beyond it a half is Inf
        std::vector<Imath::half> in(3 * std::size_t(count));
        for (std::size_t i = 0; i < in.size(); ++i)
            in[i] = Imath::half(std::isfinite(rgb[i]) ? std::clamp(rgb[i], -kHalfMax, kHalfMax) : 0.0f);
        OCIO::PackedImageDesc src(in.data(), count, 1, OCIO::CHANNEL_ORDERING_RGB, OCIO::BIT_DEPTH_F16, 2, 6, 6 * std::ptrdiff_t(count));
        OCIO::PackedImageDesc dst(out, count, 1, OCIO::CHANNEL_ORDERING_RGB, OCIO::BIT_DEPTH_UINT8, 1, 3, 3 * std::ptrdiff_t(count));
        cpu_->apply(src, dst);
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

void xyzToSceneLinear(float* xyz, int count) {
    const OCIO::ConstConfigRcPtr config = activeConfig();
    if (!config->hasRole(OCIO::ROLE_INTERCHANGE_DISPLAY))
        throw Error(std::string("colour management: config '") + config->getName() + "' has no '" + OCIO::ROLE_INTERCHANGE_DISPLAY +
                    "' role (CIE XYZ D65), which blackbody emission needs");
    try {
        const auto cpu = config->getProcessor(OCIO::ROLE_INTERCHANGE_DISPLAY, OCIO::ROLE_SCENE_LINEAR)->getDefaultCPUProcessor();
        OCIO::PackedImageDesc desc(xyz, count, 1, 3);
        cpu->apply(desc);
    } catch (const OCIO::Exception& e) {
        throw Error(std::string("colour management: CIE XYZ to scene_linear: ") + e.what());
    }
}

const DisplayTransform& displayTransform() {
    static std::once_flag once;
    static std::unique_ptr<DisplayTransform> instance;
    std::call_once(once, [] { instance = std::make_unique<OcioDisplayTransform>(); });
    return *instance;
}

}  // namespace weft
