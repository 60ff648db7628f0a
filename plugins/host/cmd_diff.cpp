// weft diff A B: error metrics of A against the reference B, per channel and
// overall. --fail RMSE exits 2 when the overall RMSE is above it.
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/image/compare/image_compare.hpp"
#include "core/image/io/image_io.hpp"
#include "core/image/compare/regression_case.hpp"
#include "plugins/host/command.hpp"

namespace weft {

namespace {

struct DiffOptions {
    std::string test, reference;
    double failRmse = -1;
    double threshold = 0.004;
    std::string rule;  // a regression case.json: its pass rule decides
};

void printRow(const ChannelError& c) {
    std::printf("%-12s %12.6g %12.6g %10.3f %9.6f %12.6g\n", c.channel.c_str(), c.rmse, c.relMse, c.psnr, c.ssim, c.maxAbs);
}

void runDiff(const DiffOptions& o) {
    const Image a = readImage(o.test), b = readImage(o.reference);
    const std::optional<RegressionRule> rule = o.rule.empty() ? std::nullopt : std::optional(readRegressionCase(o.rule).rule);
    const ImageComparison cmp = compareImages(a, b, rule ? rule->threshold : o.threshold);
    std::printf("%-12s %12s %12s %10s %9s %12s\n", "channel", "RMSE", "relMSE", "PSNR", "SSIM", "maxAbs");
    for (const ChannelError& c : cmp.channels) printRow(c);
    printRow(cmp.overall);
    std::printf("pixels above %g: %lld of %lld (%.3f%%)\n", o.threshold, cmp.pixelsAbove, cmp.pixels,
                100.0 * double(cmp.pixelsAbove) / double(cmp.pixels));
    if (o.failRmse >= 0 && !(cmp.overall.rmse <= o.failRmse)) {
        std::printf("FAIL: RMSE %.6g above %.6g\n", cmp.overall.rmse, o.failRmse);
        commandExitStatus() = 2;
    }
    if (rule) {
        const std::string verdict = regressionVerdict(cmp, *rule);
        if (!verdict.empty()) std::printf("FAIL: %s\n", verdict.c_str()), commandExitStatus() = 2;
    }
}

const CommandRegistrar registrar{{"diff", 20, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("diff", "compare an image against a reference: RMSE, relMSE, PSNR, SSIM, max abs error");
    auto o = std::make_shared<DiffOptions>();
    cmd->add_option("test", o->test, "image to measure")->required();
    cmd->add_option("reference", o->reference, "reference image")->required();
    cmd->add_option("--fail", o->failRmse, "exit 2 when the overall RMSE is above this")->check(CLI::NonNegativeNumber);
    cmd->add_option("--threshold", o->threshold, "per-pixel error counted as a difference")->check(CLI::NonNegativeNumber);
    cmd->add_option("--rule", o->rule, "a regression case.json whose pass rule decides (exit 2 on failure)");
    cmd->callback([o] { runDiff(*o); });
}}};

}  // namespace

}  // namespace weft
