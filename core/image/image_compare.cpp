#include "core/image/image_compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/error.hpp"

namespace weft {

std::string regressionVerdict(const ImageComparison& c, const RegressionRule& rule) {
    const double fraction = c.pixels ? double(c.pixelsAbove) / double(c.pixels) : 0.0;
    if (fraction > rule.failFraction)
        return std::to_string(c.pixelsAbove) + " of " + std::to_string(c.pixels) + " pixels differ by more than " +
               std::to_string(rule.threshold) + " (allowed fraction " + std::to_string(rule.failFraction) + ")";
    if (!(c.overall.maxAbs <= rule.hardFail))
        return "a pixel differs by " + std::to_string(c.overall.maxAbs) + ", above the hard limit " + std::to_string(rule.hardFail);
    return "";
}

namespace {

double psnrFromMse(double mse) {
    return mse > 0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
}

// Mean SSIM over 8x8 windows (stride 4) of one channel pair.
double channelSsim(const Image& a, int ca, const Image& b, int cb) {
    constexpr int kWin = 8, kStride = 4;
    constexpr double C1 = 0.01 * 0.01, C2 = 0.03 * 0.03;
    const int w = a.width(), h = a.height();
    const int winX = std::min(kWin, w), winY = std::min(kWin, h);
    double sum = 0;
    long long windows = 0;
    for (int y0 = 0; y0 + winY <= h; y0 += kStride) {
        for (int x0 = 0; x0 + winX <= w; x0 += kStride) {
            double ma = 0, mb = 0, vaa = 0, vbb = 0, vab = 0;
            const double n = double(winX) * winY;
            for (int y = y0; y < y0 + winY; ++y)
                for (int x = x0; x < x0 + winX; ++x) ma += a.at(x, y, ca), mb += b.at(x, y, cb);
            ma /= n, mb /= n;
            for (int y = y0; y < y0 + winY; ++y)
                for (int x = x0; x < x0 + winX; ++x) {
                    const double da = a.at(x, y, ca) - ma, db = b.at(x, y, cb) - mb;
                    vaa += da * da, vbb += db * db, vab += da * db;
                }
            vaa /= n - 1 > 0 ? n - 1 : 1, vbb /= n - 1 > 0 ? n - 1 : 1, vab /= n - 1 > 0 ? n - 1 : 1;
            sum += ((2 * ma * mb + C1) * (2 * vab + C2)) / ((ma * ma + mb * mb + C1) * (vaa + vbb + C2));
            ++windows;
        }
    }
    return windows ? sum / double(windows) : 1.0;
}

}  // namespace

ImageComparison compareImages(const Image& test, const Image& reference, double threshold) {
    if (test.width() != reference.width() || test.height() != reference.height())
        throw Error("images differ in size: " + std::to_string(test.width()) + "x" + std::to_string(test.height()) + " vs " +
                    std::to_string(reference.width()) + "x" + std::to_string(reference.height()));
    std::vector<std::pair<int, int>> pairs;
    ImageComparison out;
    for (int cb = 0; cb < reference.channelCount(); ++cb)
        if (int ca = test.channelIndex(reference.channelNames()[cb]); ca >= 0) {
            pairs.emplace_back(ca, cb);
            out.channels.push_back({reference.channelNames()[cb]});
        }
    if (pairs.empty()) throw Error("the images share no channel name");

    const long long n = (long long)test.width() * test.height();
    std::vector<double> sq(pairs.size(), 0), rel(pairs.size(), 0);
    out.pixels = n;
    for (int y = 0; y < test.height(); ++y)
        for (int x = 0; x < test.width(); ++x) {
            bool above = false;
            for (std::size_t i = 0; i < pairs.size(); ++i) {
                const double a = test.at(x, y, pairs[i].first), b = reference.at(x, y, pairs[i].second);
                const double d = std::isfinite(a - b) ? a - b : std::numeric_limits<double>::infinity();
                sq[i] += d * d;
                rel[i] += d * d / (b * b + 0.01);
                out.channels[i].maxAbs = std::max(out.channels[i].maxAbs, std::abs(d));
                above = above || std::abs(d) > threshold;
            }
            out.pixelsAbove += above;
        }
    out.overall.channel = "all";
    double sqAll = 0, relAll = 0, ssimAll = 0;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        ChannelError& c = out.channels[i];
        c.rmse = std::sqrt(sq[i] / n);
        c.relMse = rel[i] / n;
        c.psnr = psnrFromMse(sq[i] / n);
        c.ssim = channelSsim(test, pairs[i].first, reference, pairs[i].second);
        sqAll += sq[i], relAll += rel[i], ssimAll += c.ssim;
        out.overall.maxAbs = std::max(out.overall.maxAbs, c.maxAbs);
    }
    const double m = double(n) * pairs.size();
    out.overall.rmse = std::sqrt(sqAll / m);
    out.overall.relMse = relAll / m;
    out.overall.psnr = psnrFromMse(sqAll / m);
    out.overall.ssim = ssimAll / pairs.size();
    return out;
}

}  // namespace weft
