#include "core/image/compare/image_spectrum.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "core/base/error.hpp"

namespace weft {

namespace {

using Complex = std::complex<double>;

// out[k] = sum_n in[n * stride] e^{-2 pi i k n / N}, with precomputed twiddles.
void dft(const Complex* in, std::size_t stride, Complex* out, const std::vector<Complex>& twiddle) {
    const std::size_t N = twiddle.size();
    for (std::size_t k = 0; k < N; ++k) {
        Complex s = 0;
        for (std::size_t n = 0; n < N; ++n) s += in[n * stride] * twiddle[(k * n) % N];
        out[k] = s;
    }
}

std::vector<Complex> twiddles(int N) {
    std::vector<Complex> t(N);
    for (int k = 0; k < N; ++k) t[k] = std::polar(1.0, -2 * std::numbers::pi * k / N);
    return t;
}

}  // namespace

std::vector<double> powerSpectrum(const std::vector<double>& image, int W, int H) {
    if (W < 1 || H < 1 || image.size() != std::size_t(W) * H) throw Error("power spectrum: image size does not match");
    const auto tw = twiddles(W), th = twiddles(H);
    std::vector<Complex> rows(image.size()), cols(image.size());
    tbb::parallel_for(0, H, [&](int y) {
        std::vector<Complex> in(image.begin() + std::size_t(y) * W, image.begin() + std::size_t(y + 1) * W);
        dft(in.data(), 1, &rows[std::size_t(y) * W], tw);
    });
    tbb::parallel_for(0, W, [&](int x) {
        std::vector<Complex> out(H);
        dft(&rows[x], W, out.data(), th);
        for (int y = 0; y < H; ++y) cols[std::size_t(y) * W + x] = out[y];
    });
    std::vector<double> power(image.size());
    for (std::size_t i = 0; i < power.size(); ++i) power[i] = std::norm(cols[i]);
    return power;
}

AliasingPeak coherentAliasing(const std::vector<double>& error, int W, int H, double excludeRadius) {
    const std::vector<double> power = powerSpectrum(error, W, H);
    AliasingPeak peak;
    double sum = 0, best = -1;
    long count = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const int fx = x <= W / 2 ? x : x - W, fy = y <= H / 2 ? y : y - H;
            if (std::hypot(fx, fy) <= excludeRadius) continue;
            const double p = power[std::size_t(y) * W + x];
            sum += p, ++count;
            if (p > best) best = p, peak.fx = fx, peak.fy = fy;
        }
    const double mean = count ? sum / count : 0;
    peak.ratio = mean > 0 ? best / mean : 0;
    return peak;
}

double blurredRms(const std::vector<double>& image, int W, int H, double sigma) {
    const int r = std::max(1, int(std::ceil(3 * sigma)));
    std::vector<double> k(2 * r + 1);
    double ks = 0;
    for (int i = -r; i <= r; ++i) ks += k[i + r] = std::exp(-0.5 * i * i / (sigma * sigma));
    for (double& v : k) v /= ks;
    auto blur = [&](const std::vector<double>& in, bool alongX) {
        std::vector<double> out(in.size(), 0.0);
        tbb::parallel_for(0, H, [&](int y) {
            for (int x = 0; x < W; ++x) {
                double s = 0;
                for (int i = -r; i <= r; ++i) {
                    const int sx = alongX ? std::clamp(x + i, 0, W - 1) : x, sy = alongX ? y : std::clamp(y + i, 0, H - 1);
                    s += k[i + r] * in[std::size_t(sy) * W + sx];
                }
                out[std::size_t(y) * W + x] = s;
            }
        });
        return out;
    };
    double sq = 0;
    for (double v : blur(blur(image, true), false)) sq += v * v;
    return std::sqrt(sq / double(image.size()));
}

}  // namespace weft
