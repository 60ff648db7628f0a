#include "oracles/oracle.hpp"

namespace weft {

OracleRegistry& oracles() {
    static OracleRegistry registry("oracle");
    return registry;
}

}  // namespace weft
