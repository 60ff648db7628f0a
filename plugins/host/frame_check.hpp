#pragma once
// Whether a rendered frame is complete, for farm scripts (`weft check` and
// the Python module's weft.check): "ok" when the whole image reads back and
// it carries weft:complete = 1 (written last into every finished render and
// merge), "missing", or "corrupt: WHY" (one line).
#include <string>

namespace weft {

std::string frameState(const std::string& path);

}  // namespace weft
