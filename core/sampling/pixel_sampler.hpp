#pragma once
// Sampling building blocks for the mesh techniques: a stratified sampler
// whose values are pure functions of (seed, pixel, sample, dimension), and
// the warps from the unit square to directions.
#include <cmath>
#include <cstdint>

#include "core/scene/camera.hpp"
#include "core/base/rng.hpp"

namespace weft {

// A random permutation of [0, n) keyed by `key`, evaluated at i (Kensler's
// hash-based permutation, "Correlated Multi-Jittered Sampling", 2013).
constexpr std::uint32_t permuteIndex(std::uint32_t i, std::uint32_t n, std::uint32_t key) {
    std::uint32_t w = n - 1;
    w |= w >> 1, w |= w >> 2, w |= w >> 4, w |= w >> 8, w |= w >> 16;
    do {
        i ^= key, i *= 0xe170893du, i ^= key >> 16, i ^= (i & w) >> 4, i ^= key >> 8, i *= 0x0929eb3fu;
        i ^= key >> 23, i ^= (i & w) >> 1, i *= 1u | key >> 27, i *= 0x6935fa69u, i ^= (i & w) >> 11;
        i *= 0x74dcb303u, i ^= (i & w) >> 2, i *= 0x9e501cc3u, i ^= (i & w) >> 2, i *= 0xc860a3dfu;
        i &= w, i ^= i >> 5;
    } while (i >= n);
    return (i + key) % n;
}

// Sample `sample` of `count` at one pixel: every dimension is stratified into
// `count` strata, with an independent random order of strata per dimension
// (a Latin hypercube over the pixel's samples).
class PixelSampler {
public:
    PixelSampler(std::uint64_t seed, int x, int y, std::uint32_t sample, std::uint32_t count)
        : sample_(sample), count_(count ? count : 1) {
        const std::uint64_t pixel = (std::uint64_t(std::uint32_t(x)) << 32) | std::uint32_t(y);
        strataKey_ = hashCombine(seed, pixel);
        jitterKey_ = hashCombine(mix64(seed ^ 0x5bd1e995ull), pixel);  // pixelRandom(seed ^ 0x5bd1e995, x, y, ...)'s first step
    }
    float get(std::uint32_t dim) const {
        const auto key = std::uint32_t(hashCombine(strataKey_, dim));
        const std::uint32_t stratum = permuteIndex(sample_ % count_, count_, key);
        const float jitter = toUnitFloat(hashCombine(jitterKey_, (std::uint64_t(sample_) << 32) | dim));
        const float u = (float(stratum) + jitter) / float(count_);
        return u < 1.0f ? u : 0x1.fffffep-1f;
    }

private:
    // The per-pixel halves of the hashes, computed once: a path asks for
    // eight dimensions per vertex, and the hashes were a fifth of a path
    // tracer's time.
    std::uint64_t strataKey_, jitterKey_;
    std::uint32_t sample_, count_;
};

// The PixelSampler dimension of a camera sample's shutter time: one no path
// vertex reaches (paths use dimensions 2 and up, 8 per vertex).
constexpr std::uint32_t kShutterDim = 1u << 24;

// An orthonormal frame around a unit vector (Duff et al. 2017).
struct Frame {
    Vec3f t, b, n;
    explicit Frame(const Vec3f& normal) : n(normal) {
        const float sign = std::copysign(1.0f, n.z());
        const float a = -1.0f / (sign + n.z());
        const float c = n.x() * n.y() * a;
        t = Vec3f(1.0f + sign * n.x() * n.x() * a, sign * c, -sign * n.x());
        b = Vec3f(c, sign + n.y() * n.y() * a, -n.y());
    }
    Vec3f toWorld(float x, float y, float z) const { return t * x + b * y + n * z; }
};

// Cosine-weighted direction around n; pdf = cos / pi.
inline Vec3f sampleCosine(const Vec3f& n, float u, float v) {
    const float r = std::sqrt(u), phi = float(2.0 * M_PI) * v;
    return Frame(n).toWorld(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u)));
}

// Direction around axis with density (e + 1) / (2 pi) * cos^e.
inline Vec3f samplePhongLobe(const Vec3f& axis, float exponent, float u, float v) {
    const float cosT = std::pow(u, 1.0f / (exponent + 1.0f));
    const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT)), phi = float(2.0 * M_PI) * v;
    return Frame(axis).toWorld(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
}

// Uniform direction on the sphere; pdf = 1 / (4 pi).
inline Vec3f sampleSphere(float u, float v) {
    const float z = 1.0f - 2.0f * u, r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = float(2.0 * M_PI) * v;
    return Vec3f(r * std::cos(phi), r * std::sin(phi), z);
}

}  // namespace weft
