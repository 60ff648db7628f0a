#include "core/screen/discontinuity.hpp"

#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>

namespace weft {

bool similarTexels(const GTexel& a, const GTexel& b, const DiscontinuityThresholds& t) {
    if (a.background() || b.background()) return a.background() == b.background();
    if (a.normal.dot(b.normal) < t.normalCos) return false;
    return (a.position - b.position).length() <= t.position * std::max(a.depth, b.depth);
}

std::vector<std::uint8_t> discontinuityBuffer(const GBuffer& g, const DiscontinuityThresholds& t) {
    std::vector<std::uint8_t> out(g.texels.size(), 0);
    tbb::parallel_for(0, g.height, [&](int y) {
        for (int x = 0; x < g.width; ++x) {
            const GTexel& c = g.at(x, y);
            bool disc = false;
            if (x + 1 < g.width) disc |= !similarTexels(c, g.at(x + 1, y), t);
            if (y + 1 < g.height) disc |= !similarTexels(c, g.at(x, y + 1), t);
            if (x + 1 < g.width && y + 1 < g.height) disc |= !similarTexels(c, g.at(x + 1, y + 1), t);
            out[std::size_t(y) * g.width + x] = disc ? 1 : 0;
        }
    });
    return out;
}

namespace {

// One direction of the separable blur: along x or along y. C channels of
// each `stride` floats (C fixed at compile time for the common counts).
template <int C>
void blurPass(const float* src, float* dst, int width, int height, int stride, int channels,
              const std::vector<std::uint8_t>& disc, const std::vector<float>& weights, bool alongX) {
    const int radius = int(weights.size()) - 1;
    const int nc = C > 0 ? C : channels;
    tbb::parallel_for(0, height, [&](int y) {
        float acc[64];
        const int len = alongX ? width : height;
        for (int x = 0; x < width; ++x) {
            const int pos = alongX ? x : y;
            const std::size_t base = std::size_t(y) * width + x;
            const std::ptrdiff_t step = alongX ? 1 : width;  // pixels between neighbours
            auto at = [&](int k) { return std::size_t(std::ptrdiff_t(base) + (k - pos) * step); };
            float wsum = weights[0];
            for (int c = 0; c < nc; ++c) acc[c] = weights[0] * src[base * stride + c];
            auto add = [&](int k, float w) {
                wsum += w;
                const float* p = src + at(k) * stride;
                for (int c = 0; c < nc; ++c) acc[c] += w * p[c];
            };
            for (int k = 1; k <= radius && pos + k < len && !disc[at(pos + k - 1)]; ++k) add(pos + k, weights[std::size_t(k)]);
            for (int k = 1; k <= radius && pos - k >= 0 && !disc[at(pos - k)]; ++k) add(pos - k, weights[std::size_t(k)]);
            const float inv = 1.0f / wsum;
            for (int c = 0; c < nc; ++c) dst[base * stride + c] = acc[c] * inv;
        }
    });
}

template <int C>
void blurBoth(float* data, float* tmp, int width, int height, int stride, int channels,
              const std::vector<std::uint8_t>& disc, const std::vector<float>& weights) {
    blurPass<C>(data, tmp, width, height, stride, channels, disc, weights, true);
    blurPass<C>(tmp, data, width, height, stride, channels, disc, weights, false);
}

}  // namespace

void discontinuityBlur(float* data, float* scratch, int width, int height, int stride, int channels,
                       const std::vector<std::uint8_t>& discontinuity, int radius) {
    if (radius <= 0 || channels <= 0) return;
    if (channels > 64) throw std::invalid_argument("discontinuityBlur: at most 64 channels");
    const float sigma = 0.5f * float(radius);
    std::vector<float> weights(std::size_t(radius) + 1);
    for (int k = 0; k <= radius; ++k) weights[std::size_t(k)] = std::exp(-0.5f * float(k * k) / (sigma * sigma));
    if (channels == 6) blurBoth<6>(data, scratch, width, height, stride, channels, discontinuity, weights);
    else if (channels == 12) blurBoth<12>(data, scratch, width, height, stride, channels, discontinuity, weights);
    else blurBoth<0>(data, scratch, width, height, stride, channels, discontinuity, weights);
}

void discontinuityBlur(float* data, int width, int height, int stride, int channels,
                       const std::vector<std::uint8_t>& discontinuity, int radius) {
    if (radius <= 0 || channels <= 0) return;
    FreshBuffer<float> scratch(std::size_t(width) * height * stride);
    discontinuityBlur(data, scratch.data(), width, height, stride, channels, discontinuity, radius);
}

}  // namespace weft
