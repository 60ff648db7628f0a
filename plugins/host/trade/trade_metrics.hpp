#pragma once
// The error of a render against its reference, as weft sweep and weft tune
// report it: the beauty image only (R, G, B, A; AOVs are not the picture),
// with core/image/compare/image_compare.hpp's metrics and LDR-FLIP (core/image/compare/flip.hpp).
#include <string>
#include <vector>

#include "core/image/compare/flip.hpp"
#include "core/image/image.hpp"

namespace weft {

struct TradeError {
    double rmse = 0, relMse = 0, psnr = 0, ssim = 1, maxAbs = 0, flip = 0;
};

// Throws when the sizes differ or either image lacks R, G, B or A.
TradeError measureTradeError(const Image& test, const Image& reference);

// A reference prepared once (its beauty and FLIP's filtering of it) for the
// many renders a sweep or a search measures against it; measure(test)
// equals measureTradeError(test, reference).
class TradeReference {
public:
    explicit TradeReference(const Image& reference);  // throws when it lacks R, G, B or A
    TradeError measure(const Image& test) const;

private:
    Image beauty_;
    FlipReference flip_;
};

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
