#pragma once
// Edge-avoiding A-Trous wavelet filter (Dammertz et al. 2010), as Bauszat et
// al. 2011 write it (their Eq. 1-6): level i convolves the image with the 5x5
// B3-spline kernel h = (1/16, 1/4, 3/8, 1/4, 1/16)^2 whose taps are spread
// 2^i pixels apart, each tap q of pixel p weighted by
//   h(q) exp(-|c_p - c_q|^2 / sc^2) exp(-|N_p - N_q|^2 / sn^2) exp(-|P_p - P_q|^2 / sp^2)
// and the sum divided by W_p, the sum of those weights. Colour distances are
// taken on the current level's image; sc is multiplied by `colorDecay` after
// each level. An infinite sigma switches its term off (infinite sigmas give
// the plain B3 a-trous smoothing).
//
// Robustness: taps outside the image are left out (W_p renormalises); a
// pixel's own tap always has weight h(0), so W_p > 0 whenever its colour is
// finite. Non-finite colours are treated as missing samples (weight 0; a
// missing pixel is filled from its neighbours, or 0 when it has none), and
// non-finite or zero normals/positions (background) only lower weights:
// nothing the filter writes is NaN or Inf.
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "core/image/image.hpp"

namespace weft {

// Per-pixel 3-vectors as three planes (x, y, z), row-major: N and P guides.
struct VectorPlanes {
    std::array<std::vector<float>, 3> c;
    bool empty() const { return c[0].empty(); }
    void resize(std::size_t n) {
        for (auto& p : c) p.assign(n, 0.0f);
    }
    void set(std::size_t i, float x, float y, float z) { c[0][i] = x, c[1][i] = y, c[2][i] = z; }
};

// The geometry a filter is guided by; a plane set may be empty when its
// sigma is infinite.
struct GeometryGuides {
    int width = 0, height = 0;
    VectorPlanes normal;    // unit normals; zero for background
    VectorPlanes position;  // world-space hit points
};

struct AtrousSettings {
    static constexpr float kOff = std::numeric_limits<float>::infinity();
    int levels = 5;              // >= 0; level i spreads the taps 2^i pixels apart
    float sigmaColor = kOff;     // > 0; kOff: colour term off
    float sigmaNormal = kOff;
    float sigmaPosition = kOff;  // scene units
    float colorDecay = 1.0f;     // sigmaColor is multiplied by this after each level, in (0, 1]
};

// Throws weft::Error naming the setting when one is out of range.
void validate(const AtrousSettings& settings);

// Optional per-pixel weights that multiply every tap of a pixel (its own
// included) on the first `levels` levels: a pixel's sample count makes the
// first level pool samples, as if every pixel's samples were averaged
// together, instead of averaging pixel means of unequal quality. Empty: 1.
// Weights must be finite and >= 0; a pixel of weight 0 counts as a missing
// sample on those levels.
struct TapWeights {
    static constexpr int kAllLevels = std::numeric_limits<int>::max();
    std::vector<float> perPixel;
    int levels = 0;
};

// Filters `color` (3 floats per pixel, row-major, width x height) in place.
void atrousFilter(float* color, std::size_t size, int width, int height, const GeometryGuides& guides,
                  const AtrousSettings& settings, const TapWeights& tapWeights = {});
inline void atrousFilter(std::vector<float>& color, int width, int height, const GeometryGuides& guides,
                         const AtrousSettings& settings, const TapWeights& tapWeights = {}) {
    atrousFilter(color.data(), color.size(), width, height, guides, settings, tapWeights);
}

// The B3-spline taps h(-2..2).
constexpr std::array<float, 5> kB3Taps = {1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16};

// Exponent of a geometry range weight: |a-b|^2 * invSigma2 summed over the
// guides given (invSigma2 = 1/sigma^2, 0 when off).
inline float distance2(const VectorPlanes& v, std::size_t a, std::size_t b) {
    const float dx = v.c[0][a] - v.c[0][b], dy = v.c[1][a] - v.c[1][b], dz = v.c[2][a] - v.c[2][b];
    return dx * dx + dy * dy + dz * dz;
}

// 1/sigma^2, 0 for an infinite sigma.
inline float inverseSquare(float sigma) { return sigma == AtrousSettings::kOff ? 0.0f : 1.0f / (sigma * sigma); }

// Image-level filter: channels `layer`.R/G/B (R, G, B when the layer is
// empty) of `image`, guided by `normalLayer`.X/Y/Z and `positionLayer`.X/Y/Z
// when their sigmas are finite, every tap weighted by channel
// `weightChannel` on every level when it is not empty (e.g. sampleCount).
// Missing channels are one error naming them.
void atrousFilterImage(Image& image, const std::string& layer, const std::string& normalLayer,
                       const std::string& positionLayer, const AtrousSettings& settings,
                       const std::string& weightChannel = "");

}  // namespace weft
