#include "plugins/technique.hpp"

namespace weft {

TechniqueRegistry& techniques() {
    static TechniqueRegistry registry("technique");
    return registry;
}

}  // namespace weft
