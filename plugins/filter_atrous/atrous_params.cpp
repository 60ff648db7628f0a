#include "plugins/filter_atrous/atrous_params.hpp"

namespace weft {

std::vector<ParamSpec> atrousParamSpecs() {
    return {
        intParam("levels", 5, 0, 24, "A-Trous levels; level i spreads the 5x5 B3 taps 2^i pixels apart"),
        floatParam("sigma_color", 0, 0, 1e30, "colour range sigma (Eq. 3) on the current level's image; 0 = term off"),
        floatParam("sigma_normal", 0.3, 0, 1e30, "normal range sigma (Eq. 4); 0 = term off"),
        floatParam("sigma_position", 0.1, 0, 1e30, "position range sigma (Eq. 5) in scene units; 0 = term off"),
        floatParam("color_decay", 0.5, 1e-6, 1, "sigma_color is multiplied by this after each level"),
    };
}

AtrousSettings atrousSettingsFrom(const ParamSet& p) {
    auto sigma = [&](const char* key) {
        const double v = p.getFloat(key);
        return v > 0 ? float(v) : AtrousSettings::kOff;
    };
    AtrousSettings s;
    s.levels = int(p.getInt("levels"));
    s.sigmaColor = sigma("sigma_color");
    s.sigmaNormal = sigma("sigma_normal");
    s.sigmaPosition = sigma("sigma_position");
    s.colorDecay = float(p.getFloat("color_decay"));
    return s;
}

}  // namespace weft
