#pragma once
// The error of a render against its reference, as weft sweep and weft tune
// report it: the beauty image only (R, G, B, A; AOVs are not the picture),
// with core/image/image_compare.hpp's metrics and LDR-FLIP (core/image/flip.hpp).
#include <string>
#include <vector>

#include "core/image/image.hpp"

namespace weft {

struct TradeError {
    double rmse = 0, relMse = 0, psnr = 0, ssim = 1, maxAbs = 0, flip = 0;
};

// Throws when the sizes differ or either image lacks R, G, B or A.
TradeError measureTradeError(const Image& test, const Image& reference);

// The metrics by name, as --metric and --target spell them.
enum class TradeMetric { Rmse, RelMse, Psnr, Ssim, Flip, MaxAbs };
TradeMetric parseTradeMetric(const std::string& name);  // rmse|relmse|psnr|ssim|flip|maxabs
const char* tradeMetricName(TradeMetric metric);
double metricValue(const TradeError& e, TradeMetric metric);
// Whether larger is better (PSNR, SSIM); the others are errors.
bool higherIsBetter(TradeMetric metric);
// The metric as an error to minimise (PSNR and SSIM negated), for fronts.
double metricAsError(const TradeError& e, TradeMetric metric);

}  // namespace weft
