#include "core/volume/optics/blackbody.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <string>

#include "core/base/error.hpp"
#include "core/image/color.hpp"
#include "core/volume/optics/cie1931.hpp"

namespace weft {

namespace {

constexpr int kEntries = 1024;
constexpr double kMiredLo = 1e6 / kBlackbodyHottestK, kMiredHi = 1e6 / kBlackbodyColdestK;

// Planck's law up to a constant factor (it cancels when Y is normalised):
// lambda^-5 / (exp(c2 / (lambda T)) - 1), lambda in metres.
double planckShape(double lambda, double kelvin) {
    constexpr double c2 = 1.438776877e-2;  // h c / k, m K (CODATA 2018)
    return 1.0 / (std::pow(lambda, 5) * std::expm1(c2 / (lambda * kelvin)));
}

}  // namespace

Vec3d blackbodyXyz(double kelvin) {
    const double t = std::clamp(std::isfinite(kelvin) ? kelvin : kBlackbodyColdestK, kBlackbodyColdestK, kBlackbodyHottestK);
    Vec3d xyz(0.0);
    for (int i = 0; i < cie1931::kCount; ++i) {
        const double b = planckShape((cie1931::kFirstNm + i * cie1931::kStepNm) * 1e-9, t);
        xyz += Vec3d(cie1931::kXBar[i], cie1931::kYBar[i], cie1931::kZBar[i]) * b;
    }
    return xyz / xyz.y();
}

BlackbodyTable::BlackbodyTable() {
    std::vector<float> xyz(3 * kEntries);
    for (int i = 0; i < kEntries; ++i) {
        const double mired = kMiredLo + (kMiredHi - kMiredLo) * i / (kEntries - 1);
        const Vec3d c = blackbodyXyz(1e6 / mired);
        for (int k = 0; k < 3; ++k) xyz[3 * i + k] = float(c[k]);
    }
    xyzToSceneLinear(xyz.data(), kEntries);
    rgb_.resize(kEntries);
    for (int i = 0; i < kEntries; ++i)
        for (int k = 0; k < 3; ++k) rgb_[i][k] = std::isfinite(xyz[3 * i + k]) ? std::max(0.0f, xyz[3 * i + k]) : 0.0f;
}

const BlackbodyTable& BlackbodyTable::get() {
    static std::once_flag once;
    static std::unique_ptr<BlackbodyTable> table;
    static std::string error;
    std::call_once(once, [] {
        try {
            table.reset(new BlackbodyTable());
        } catch (const Error& e) {
            error = e.what();
        }
    });
    if (!table) throw Error(error);
    return *table;
}

Vec3f BlackbodyTable::color(double kelvin) const {
    const double t = std::clamp(std::isfinite(kelvin) ? kelvin : kBlackbodyColdestK, kBlackbodyColdestK, kBlackbodyHottestK);
    const double x = (1e6 / t - kMiredLo) / (kMiredHi - kMiredLo) * (kEntries - 1);
    const int i = std::clamp(int(x), 0, kEntries - 2);
    const float w = float(std::clamp(x - i, 0.0, 1.0));
    return rgb_[i] + (rgb_[i + 1] - rgb_[i]) * w;
}

}  // namespace weft
