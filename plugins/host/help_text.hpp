#pragma once
// The text `weft help NAME` prints, for the other front ends (the Python module).
#include <string>

#include "plugins/technique.hpp"

namespace weft {

std::string techniqueHelpText(const TechniqueInfo& t);

}  // namespace weft
