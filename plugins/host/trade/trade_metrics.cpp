#include "plugins/host/trade/trade_metrics.hpp"

#include "core/base/error.hpp"
#include "core/image/compare/image_compare.hpp"

namespace weft {

namespace {

constexpr const char* kBeauty[] = {"R", "G", "B", "A"};

void requireBeauty(const Image& img, const char* role) {
    for (const char* c : kBeauty)
        if (img.channelIndex(c) < 0) throw Error(std::string("the ") + role + " has no " + c + " channel");
}

Image beautyOf(const Image& img, const char* role) {
    requireBeauty(img, role);
    Image out(img.width(), img.height(), {kBeauty, kBeauty + 4});
    int index[4];
    for (int c = 0; c < 4; ++c) index[c] = img.channelIndex(kBeauty[c]);
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
            for (int c = 0; c < 4; ++c) out.at(x, y, c) = img.at(x, y, index[c]);
    return out;
}

struct MetricName {
    const char* name;
    TradeMetric metric;
};
constexpr MetricName kMetrics[] = {{"rmse", TradeMetric::Rmse}, {"relmse", TradeMetric::RelMse}, {"psnr", TradeMetric::Psnr},
                                   {"ssim", TradeMetric::Ssim}, {"flip", TradeMetric::Flip},     {"maxabs", TradeMetric::MaxAbs}};

void checkSameSize(const Image& test, const Image& reference) {
    if (test.width() != reference.width() || test.height() != reference.height())
        throw Error("the render is " + std::to_string(test.width()) + "x" + std::to_string(test.height()) + " but the reference is " +
                    std::to_string(reference.width()) + "x" + std::to_string(reference.height()));
}

}  // namespace

TradeReference::TradeReference(const Image& reference) : beauty_(beautyOf(reference, "reference")), flip_(beauty_) {}

// The render is used as it is: compareImages takes the reference's channels
// (the beauty) by name, and FLIP reads R, G and B by name.
TradeError TradeReference::measure(const Image& test) const {
    checkSameSize(test, beauty_);
    requireBeauty(test, "render");
    const ChannelError all = compareImages(test, beauty_).overall;
    return {all.rmse, all.relMse, all.psnr, all.ssim, all.maxAbs, flip_.meanError(test)};
}

TradeError measureTradeError(const Image& test, const Image& reference) {
    checkSameSize(test, reference);
    requireBeauty(test, "render");  // the render's missing channel is named before the reference's
    return TradeReference(reference).measure(test);
}

TradeMetric parseTradeMetric(const std::string& name) {
    for (const MetricName& m : kMetrics)
        if (name == m.name) return m.metric;
    throw Error("metric '" + name + "': expected rmse, relmse, psnr, ssim, flip or maxabs");
}

const char* tradeMetricName(TradeMetric metric) {
    for (const MetricName& m : kMetrics)
        if (m.metric == metric) return m.name;
    return "?";
}

double metricValue(const TradeError& e, TradeMetric metric) {
    switch (metric) {
        case TradeMetric::Rmse: return e.rmse;
        case TradeMetric::RelMse: return e.relMse;
        case TradeMetric::Psnr: return e.psnr;
        case TradeMetric::Ssim: return e.ssim;
        case TradeMetric::Flip: return e.flip;
        case TradeMetric::MaxAbs: return e.maxAbs;
    }
    return 0;
}

bool higherIsBetter(TradeMetric metric) { return metric == TradeMetric::Psnr || metric == TradeMetric::Ssim; }

double metricAsError(const TradeError& e, TradeMetric metric) {
    const double v = metricValue(e, metric);
    return higherIsBetter(metric) ? -v : v;
}

}  // namespace weft
