#include "core/image/compare/image_compare.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <tbb/parallel_for.h>

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

// Means and centred sums of squares and products of n (a, b) pixel pairs.
// Centred sums stay exact where the means dwarf the spread (HDR values), as
// a two-pass sum does and sums of squares do not.
struct Moments {
    double n = 0, ma = 0, mb = 0, aa = 0, bb = 0, ab = 0;
    // A block of cols x rows pixels: a[y * rowA + x * pixelA], b likewise.
    static Moments ofBlock(const float* a, std::size_t pixelA, std::size_t rowA, const float* b, std::size_t pixelB,
                           std::size_t rowB, int cols, int rows) {
        Moments m;
        m.n = double(cols) * rows;
        for (int y = 0; y < rows; ++y)
            for (int x = 0; x < cols; ++x) m.ma += a[y * rowA + x * pixelA], m.mb += b[y * rowB + x * pixelB];
        m.ma /= m.n, m.mb /= m.n;
        for (int y = 0; y < rows; ++y)
            for (int x = 0; x < cols; ++x) {
                const double da = a[y * rowA + x * pixelA] - m.ma, db = b[y * rowB + x * pixelB] - m.mb;
                m.aa += da * da, m.bb += db * db, m.ab += da * db;
            }
        return m;
    }
    // Blocks of equal counts joined: the mean of their means, and each
    // block's centred sums moved to that mean (the parallel axis theorem).
    static Moments join(const Moments* blocks, int count) {
        Moments m;
        for (int i = 0; i < count; ++i) m.ma += blocks[i].ma, m.mb += blocks[i].mb;
        m.ma /= count, m.mb /= count;
        for (int i = 0; i < count; ++i) {
            const Moments& c = blocks[i];
            const double da = c.ma - m.ma, db = c.mb - m.mb;
            m.aa += c.aa + c.n * da * da, m.bb += c.bb + c.n * db * db, m.ab += c.ab + c.n * da * db;
            m.n += c.n;
        }
        return m;
    }
};

// SSIM of one window from its moments (sample variances).
double windowSsim(const Moments& m) {
    constexpr double C1 = 0.01 * 0.01, C2 = 0.03 * 0.03;
    const double dof = m.n - 1 > 0 ? m.n - 1 : 1;
    const double vaa = m.aa / dof, vbb = m.bb / dof, vab = m.ab / dof;
    return ((2 * m.ma * m.mb + C1) * (2 * vab + C2)) / ((m.ma * m.ma + m.mb * m.mb + C1) * (vaa + vbb + C2));
}

// Mean SSIM over 8x8 windows (stride 4) of one channel pair. A window is
// 2x2 blocks of 4x4 pixels (one block across, or down, where the image is
// narrower than a window), so each block's moments are taken once and
// joined into the four windows that overlap it. Bands of blocks, then rows
// of windows, run in parallel, each row summed alone, then the rows in
// order: the same on any thread count.
double channelSsim(const Image& a, int ca, const Image& b, int cb) {
    constexpr int kWin = 8, kStride = 4;
    const int w = a.width(), h = a.height();
    if (w == 0 || h == 0) return 1.0;  // nothing differs
    const int winX = std::min(kWin, w), winY = std::min(kWin, h);
    const int rows = (h - winY) / kStride + 1, perRow = (w - winX) / kStride + 1;
    const int blockW = winX == kWin ? kStride : winX, blockH = winY == kWin ? kStride : winY;
    const int acrossWindow = winX / blockW, downWindow = winY / blockH;
    const int bands = rows + downWindow - 1, perBand = perRow + acrossWindow - 1;
    const std::size_t na = a.channelCount(), nb = b.channelCount();
    std::vector<Moments> blocks(std::size_t(bands) * perBand);
    tbb::parallel_for(0, bands, [&](int band) {
        for (int j = 0; j < perBand; ++j)
            blocks[std::size_t(band) * perBand + j] =
                Moments::ofBlock(a.pixel(j * blockW, band * blockH) + ca, na, std::size_t(w) * na,
                                 b.pixel(j * blockW, band * blockH) + cb, nb, std::size_t(w) * nb, blockW, blockH);
    });
    std::vector<double> rowSums(rows, 0.0);
    tbb::parallel_for(0, rows, [&](int row) {
        for (int i = 0; i < perRow; ++i) {
            std::array<Moments, 4> parts;
            int n = 0;
            for (int dy = 0; dy < downWindow; ++dy)
                for (int dx = 0; dx < acrossWindow; ++dx) parts[n++] = blocks[std::size_t(row + dy) * perBand + i + dx];
            rowSums[row] += windowSsim(Moments::join(parts.data(), n));
        }
    });
    double sum = 0;
    for (double s : rowSums) sum += s;
    return sum / (double(rows) * perRow);
}

}  // namespace

ImageComparison compareImages(const Image& test, const Image& reference, double threshold) {
    if (test.width() != reference.width() || test.height() != reference.height())
        throw Error("images differ in size: " + std::to_string(test.width()) + "x" + std::to_string(test.height()) + " vs " +
                    std::to_string(reference.width()) + "x" + std::to_string(reference.height()));
    if (reference.width() == 0 || reference.height() == 0) throw Error("the images are empty (0x0): there is nothing to compare");
    std::vector<std::pair<int, int>> pairs;
    ImageComparison out;
    for (int cb = 0; cb < reference.channelCount(); ++cb)
        if (int ca = test.channelIndex(reference.channelNames()[cb]); ca >= 0) {
            pairs.emplace_back(ca, cb);
            out.channels.push_back({reference.channelNames()[cb]});
        }
    if (pairs.empty()) throw Error("the images share no channel name");

    const long long n = (long long)test.width() * test.height();
    out.pixels = n;
    // Rows in parallel, each with its own sums, then the rows in order: the
    // same figures on any thread count.
    struct RowSums {
        std::vector<double> sq, rel, maxAbs;
        long long above = 0;
    };
    std::vector<RowSums> rows(test.height(), RowSums{std::vector<double>(pairs.size(), 0), std::vector<double>(pairs.size(), 0),
                                                     std::vector<double>(pairs.size(), 0), 0});
    const int w = test.width();
    const std::size_t strideA = test.channelCount(), strideB = reference.channelCount();
    tbb::parallel_for(0, test.height(), [&](int y) {
        RowSums& r = rows[y];
        std::vector<char> above(w, 0);
        // A channel at a time along the row: the sums stay in registers.
        for (std::size_t i = 0; i < pairs.size(); ++i) {
            const float* pa = test.pixel(0, y) + pairs[i].first;
            const float* pb = reference.pixel(0, y) + pairs[i].second;
            double sq = 0, rel = 0, maxAbs = 0;
            for (int x = 0; x < w; ++x) {
                const double a = pa[x * strideA], b = pb[x * strideB];
                const double d = std::isfinite(a - b) ? a - b : std::numeric_limits<double>::infinity();
                sq += d * d;
                rel += d * d / (b * b + 0.01);
                maxAbs = std::max(maxAbs, std::abs(d));
                above[x] |= std::abs(d) > threshold;
            }
            r.sq[i] = sq, r.rel[i] = rel, r.maxAbs[i] = maxAbs;
        }
        r.above = std::count(above.begin(), above.end(), 1);
    });
    std::vector<double> sq(pairs.size(), 0), rel(pairs.size(), 0);
    for (const RowSums& r : rows) {
        for (std::size_t i = 0; i < pairs.size(); ++i) {
            sq[i] += r.sq[i], rel[i] += r.rel[i];
            out.channels[i].maxAbs = std::max(out.channels[i].maxAbs, r.maxAbs[i]);
        }
        out.pixelsAbove += r.above;
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
