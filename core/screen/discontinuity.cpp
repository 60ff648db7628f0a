#include "core/screen/discontinuity.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "core/base/memory/large_buffer.hpp"
#include "core/base/target_clones.hpp"

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

// The plain Gaussian over n contiguous floats whose neighbours k pixels
// away lie k * tap floats away, for pixels whose walk reaches the full
// radius both ways: the walk's own sums, in its order (centre, +1..+r,
// -1..-r, times 1 / the weights' sum), so the result is the same to the
// bit; over a run of pixels at once, it vectorises. Also compiled for
// AVX2, chosen at load time (no FMA either way).
WEFT_TARGET_CLONES("avx2", "default") void plainRun(const float* src, std::ptrdiff_t tap, const float* weights,
                                                       int radius, float inv, float* out, int n) {
    for (int i = 0; i < n; ++i) out[i] = weights[0] * src[i];
    for (int k = 1; k <= radius; ++k)
        for (int i = 0; i < n; ++i) out[i] += weights[k] * src[i + k * tap];
    for (int k = 1; k <= radius; ++k)
        for (int i = 0; i < n; ++i) out[i] += weights[k] * src[i - k * tap];
    for (int i = 0; i < n; ++i) out[i] *= inv;
}

constexpr std::size_t kPlainPiece = 1024;  // floats

// Per pixel of row y: 1 where the walk along the pass reaches the full
// radius both ways (inside the image, no discontinuity on the way), so
// the plain Gaussian gives its result.
std::vector<std::uint8_t> fullWalks(const std::vector<std::uint8_t>& disc, int width, int height, int y, int radius, bool alongX) {
    std::vector<std::uint8_t> full(std::size_t(width), 0);
    const std::uint8_t* row = disc.data() + std::size_t(y) * width;
    if (alongX) {
        // Steps cross the marks at x - r .. x + r - 1: a running count over that window.
        int marks = 0;
        for (int x = 0; x < std::min(2 * radius, width); ++x) marks += row[x];
        for (int x = radius; x + radius < width; ++x) {
            full[std::size_t(x)] = marks == 0;
            marks += row[x + radius] - row[x - radius];
        }
        return full;
    }
    if (y < radius || y + radius >= height) return full;
    std::vector<std::uint8_t> marked(std::size_t(width), 0);
    for (int r = y - radius; r < y + radius; ++r) {
        const std::uint8_t* m = disc.data() + std::size_t(r) * width;
        for (int x = 0; x < width; ++x) marked[std::size_t(x)] |= m[x];
    }
    for (int x = 0; x < width; ++x) full[std::size_t(x)] = !marked[std::size_t(x)];
    return full;
}

// One direction of the separable blur: along x or along y. C channels of
// each pixel's `srcStride` floats in, of its `dstStride` floats out (C
// fixed at compile time for the common counts). Pixels whose walk reaches
// the full radius both ways take the plain Gaussian over runs of pixels
// (all `srcStride` floats, into a row buffer, of which the C channels are
// kept); the others walk.
template <int C>
void blurPass(const float* src, float* dst, int width, int height, int srcStride, int dstStride, int channels,
              const std::vector<std::uint8_t>& disc, const std::vector<float>& weights, bool alongX) {
    const int radius = int(weights.size()) - 1;
    const int nc = C > 0 ? C : channels;
    float wsumFull = weights[0];
    for (int k = 1; k <= radius; ++k) wsumFull += weights[std::size_t(k)];
    for (int k = 1; k <= radius; ++k) wsumFull += weights[std::size_t(k)];
    const float invFull = 1.0f / wsumFull;
    const std::ptrdiff_t tap = alongX ? srcStride : std::ptrdiff_t(width) * srcStride;
    tbb::parallel_for(0, height, [&](int y) {
        float acc[64];
        const int len = alongX ? width : height;
        const std::vector<std::uint8_t> full = fullWalks(disc, width, height, y, radius, alongX);
        FreshBuffer<float> plain(std::size_t(width) * srcStride);  // written where `full` before it is read
        for (int x0 = 0; x0 < width;) {
            if (!full[std::size_t(x0)]) {
                ++x0;
                continue;
            }
            int x1 = x0;
            while (x1 < width && full[std::size_t(x1)]) ++x1;
            // In pieces that stay in the first-level cache across the taps.
            const std::size_t at = (std::size_t(y) * width + x0) * srcStride, n = std::size_t(x1 - x0) * srcStride;
            for (std::size_t i = 0; i < n; i += kPlainPiece)
                plainRun(src + at + i, tap, weights.data(), radius, invFull, plain.data() + std::size_t(x0) * srcStride + i,
                         int(std::min(kPlainPiece, n - i)));
            x0 = x1;
        }
        for (int x = 0; x < width; ++x) {
            const std::size_t base = std::size_t(y) * width + x;
            if (full[std::size_t(x)]) {
                for (int c = 0; c < nc; ++c) dst[base * dstStride + c] = plain[std::size_t(x) * srcStride + c];
                continue;
            }
            const int pos = alongX ? x : y;
            const std::ptrdiff_t step = alongX ? 1 : width;  // pixels between neighbours
            auto at = [&](int k) { return std::size_t(std::ptrdiff_t(base) + (k - pos) * step); };
            float wsum = weights[0];
            for (int c = 0; c < nc; ++c) acc[c] = weights[0] * src[base * srcStride + c];
            auto add = [&](int k, float w) {
                wsum += w;
                const float* p = src + at(k) * srcStride;
                for (int c = 0; c < nc; ++c) acc[c] += w * p[c];
            };
            for (int k = 1; k <= radius && pos + k < len && !disc[at(pos + k - 1)]; ++k) add(pos + k, weights[std::size_t(k)]);
            for (int k = 1; k <= radius && pos - k >= 0 && !disc[at(pos - k)]; ++k) add(pos - k, weights[std::size_t(k)]);
            const float inv = 1.0f / wsum;
            for (int c = 0; c < nc; ++c) dst[base * dstStride + c] = acc[c] * inv;
        }
    });
}

// The pass along x keeps only the blurred channels, so the pass along y
// reads `channels` floats per pixel, not `stride`.
template <int C>
void blurBoth(float* data, float* tmp, int width, int height, int stride, int channels,
              const std::vector<std::uint8_t>& disc, const std::vector<float>& weights) {
    blurPass<C>(data, tmp, width, height, stride, channels, channels, disc, weights, true);
    blurPass<C>(tmp, data, width, height, channels, stride, channels, disc, weights, false);
}

}  // namespace

void discontinuityBlur(float* data, int width, int height, int stride, int channels,
                       const std::vector<std::uint8_t>& discontinuity, int radius) {
    if (radius <= 0 || channels <= 0) return;
    if (channels > 64) throw std::invalid_argument("discontinuityBlur: at most 64 channels");
    const float sigma = 0.5f * float(radius);
    std::vector<float> weights(std::size_t(radius) + 1);
    for (int k = 0; k <= radius; ++k) weights[std::size_t(k)] = std::exp(-0.5f * float(k * k) / (sigma * sigma));
    FreshBuffer<float> scratch(std::size_t(width) * height * channels);
    if (channels == 6) blurBoth<6>(data, scratch.data(), width, height, stride, channels, discontinuity, weights);
    else if (channels == 12) blurBoth<12>(data, scratch.data(), width, height, stride, channels, discontinuity, weights);
    else blurBoth<0>(data, scratch.data(), width, height, stride, channels, discontinuity, weights);
}

}  // namespace weft
