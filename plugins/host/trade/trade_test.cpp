// The trade tools' pieces: the error of a render against its reference is
// measured on the beauty image only, with each metric as its formula gives
// it; every technique's declared reference and knobs are valid settings.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/base/rng.hpp"
#include "plugins/host/trade/trade_metrics.hpp"
#include "plugins/technique.hpp"
#include "tests/support/test_support.hpp"

namespace weft {
namespace {

Image noisyPair(Image& reference, double amplitude) {
    reference = Image(16, 12, {"R", "G", "B", "A", "N.X"});
    Image test = reference;
    Rng rng(7);
    for (std::size_t i = 0; i < reference.data().size(); ++i) {
        reference.data()[i] = float(0.2 + 0.6 * rng.uniform());
        test.data()[i] = reference.data()[i] + float(amplitude * (rng.uniform() - 0.5));
    }
    return test;
}

TEST(TradeMetrics, RmsePsnrAndMaxAbsAsTheirFormulas) {
    Image ref;
    const Image test = noisyPair(ref, 0.1);
    double sum = 0, maxAbs = 0, rel = 0;
    int n = 0;
    for (int y = 0; y < ref.height(); ++y)
        for (int x = 0; x < ref.width(); ++x)
            for (int c = 0; c < 4; ++c) {  // the normal channel is not the picture
                const double d = double(test.at(x, y, c)) - ref.at(x, y, c);
                sum += d * d, maxAbs = std::max(maxAbs, std::fabs(d)), ++n;
                rel += d * d / (double(ref.at(x, y, c)) * ref.at(x, y, c) + 0.01);
            }
    const TradeError e = measureTradeError(test, ref);
    EXPECT_NEAR(e.rmse, std::sqrt(sum / n), 1e-6);
    EXPECT_NEAR(e.relMse, rel / n, 1e-6);
    EXPECT_NEAR(e.psnr, 10 * std::log10(n / sum), 1e-4);
    EXPECT_NEAR(e.maxAbs, maxAbs, 1e-6);
    EXPECT_GT(e.flip, 0.0);
    EXPECT_LT(e.ssim, 1.0);
}

TEST(TradeMetrics, AovsDoNotCountAndIdenticalImagesAreExact) {
    Image ref;
    noisyPair(ref, 0);
    Image test = ref;
    for (int y = 0; y < ref.height(); ++y)
        for (int x = 0; x < ref.width(); ++x) test.at(x, y, 4) = 100;
    const TradeError e = measureTradeError(test, ref);
    EXPECT_EQ(e.rmse, 0.0);
    EXPECT_EQ(e.flip, 0.0);
    EXPECT_EQ(e.ssim, 1.0);
    EXPECT_NE(test::errorOf([&] { measureTradeError(Image(4, 4, {"R", "G", "B", "A"}), ref); }).find("4x4"), std::string::npos);
    EXPECT_NE(test::errorOf([&] { measureTradeError(Image(16, 12, {"R", "G", "B"}), ref); }).find("no A channel"), std::string::npos);
}

TEST(TradeMetrics, MetricNamesAndDirections) {
    for (const char* name : {"rmse", "relmse", "psnr", "ssim", "flip", "maxabs"})
        EXPECT_STREQ(tradeMetricName(parseTradeMetric(name)), name);
    EXPECT_NE(test::errorOf([] { parseTradeMetric("mse"); }).find("expected rmse"), std::string::npos);
    const TradeError e{0.1, 0.2, 30, 0.9, 0.5, 0.05};
    EXPECT_EQ(metricAsError(e, TradeMetric::Psnr), -30);
    EXPECT_EQ(metricAsError(e, TradeMetric::Flip), 0.05);
}

std::map<std::string, std::string> keyValues(const std::vector<std::string>& sets) {
    std::map<std::string, std::string> m;
    for (const std::string& kv : sets) m[kv.substr(0, kv.find('='))] = kv.substr(kv.find('=') + 1);
    return m;
}

TEST(TradeDeclarations, EveryTechniqueHasAValidReferenceAndKnobs) {
    for (const TechniqueInfo* t : techniques().all()) {
        SCOPED_TRACE(t->name);
        if (t->name.rfind("example.", 0) == 0) continue;  // the external example plugin declares none
        ASSERT_FALSE(t->reference.technique.empty());
        const TechniqueInfo& ref = techniques().get(t->reference.technique);
        EXPECT_NO_THROW(ref.params.parse(keyValues(t->reference.sets)));
        EXPECT_GE(t->reference.spp, 1);
        ASSERT_FALSE(t->knobs.empty());
        for (const TradeKnob& k : t->knobs) {
            ASSERT_FALSE(k.values.empty()) << k.key;
            for (const std::string& v : k.values) {
                if (k.key == "spp") EXPECT_GE(std::stoi(v), 1);
                else EXPECT_NO_THROW(t->params.parse({{k.key, v}})) << k.key << "=" << v;
            }
        }
    }
}

}  // namespace
}  // namespace weft
