#include "core/discontinuity.hpp"

#include <tbb/parallel_for.h>

#include <cmath>

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

// One direction of the separable blur: along x (stride 1) or y (stride width).
void blurPass(const std::vector<float>& src, std::vector<float>& dst, int width, int height, int channels,
              const std::vector<std::uint8_t>& disc, const std::vector<float>& weights, bool alongX) {
    const int radius = int(weights.size()) - 1;
    tbb::parallel_for(0, height, [&](int y) {
        std::vector<float> acc(static_cast<std::size_t>(channels), 0.0f);
        for (int x = 0; x < width; ++x) {
            const int len = alongX ? width : height, pos = alongX ? x : y;
            auto at = [&](int k) { return alongX ? std::size_t(y) * width + k : std::size_t(k) * width + x; };
            float wsum = weights[0];
            for (int c = 0; c < channels; ++c) acc[std::size_t(c)] = weights[0] * src[at(pos) * channels + c];
            auto add = [&](int k, float w) {
                wsum += w;
                for (int c = 0; c < channels; ++c) acc[std::size_t(c)] += w * src[at(k) * channels + c];
            };
            for (int k = 1; k <= radius && pos + k < len && !disc[at(pos + k - 1)]; ++k) add(pos + k, weights[std::size_t(k)]);
            for (int k = 1; k <= radius && pos - k >= 0 && !disc[at(pos - k)]; ++k) add(pos - k, weights[std::size_t(k)]);
            for (int c = 0; c < channels; ++c) dst[at(pos) * channels + c] = acc[std::size_t(c)] / wsum;
        }
    });
}

}  // namespace

void discontinuityBlur(std::vector<float>& data, int width, int height, int channels,
                       const std::vector<std::uint8_t>& discontinuity, int radius) {
    if (radius <= 0) return;
    const float sigma = 0.5f * float(radius);
    std::vector<float> weights(std::size_t(radius) + 1);
    for (int k = 0; k <= radius; ++k) weights[std::size_t(k)] = std::exp(-0.5f * float(k * k) / (sigma * sigma));
    std::vector<float> tmp(data.size());
    blurPass(data, tmp, width, height, channels, discontinuity, weights, true);
    blurPass(tmp, data, width, height, channels, discontinuity, weights, false);
}

}  // namespace weft
