// minimum: always the minimum sampling distance (one slice). Adaptive
// sampling then samples everything: it measures the algorithm's worst-case
// overhead and must give the same image as fixed-rate pre-integration.
#include "oracles/oracle.hpp"

namespace weft {

namespace {

const OracleRegistrar registrar{{
    "minimum",
    "always the minimum distance (worst-case overhead; same image as volume.preint)",
    [](const OracleContext& ctx) {
        OracleField field;
        field.constant = float(ctx.sliceSpacing);
        return field;
    },
}};

}  // namespace

}  // namespace weft
