#pragma once
// The edge-avoiding A-Trous filter's parameters, declared once and shared by
// `weft filter atrous` and the techniques that filter with it.
#include <vector>

#include "core/screen/atrous.hpp"
#include "core/base/options/params.hpp"

namespace weft {

// levels, sigma_color, sigma_normal, sigma_position, color_decay (a sigma of
// 0 switches its term off, i.e. an infinite sigma).
std::vector<ParamSpec> atrousParamSpecs();
AtrousSettings atrousSettingsFrom(const ParamSet& params);

}  // namespace weft
