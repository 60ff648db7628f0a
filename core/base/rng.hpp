#pragma once
// Counter-based random numbers: a value is a pure function of (seed, pixel,
// sample index, dimension), so results never depend on thread scheduling.
#include <cstdint>

namespace weft {

// SplitMix64 finaliser: a strong 64-bit mixing function.
constexpr std::uint64_t mix64(std::uint64_t z) {
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

constexpr std::uint64_t hashCombine(std::uint64_t h, std::uint64_t v) { return mix64(h ^ mix64(v)); }

// Uniform in [0, 1): the top 24 bits, so the float is exact and never 1.
constexpr float toUnitFloat(std::uint64_t bits) {
    return static_cast<float>(bits >> 40) * (1.0f / 16777216.0f);
}

// Uniform in [0, 1) for a pixel, a sample index and a dimension.
constexpr float pixelRandom(std::uint64_t seed, int x, int y, std::uint32_t sample, std::uint32_t dim) {
    std::uint64_t h = hashCombine(mix64(seed), (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) |
                                                   static_cast<std::uint32_t>(y));
    h = hashCombine(h, (static_cast<std::uint64_t>(sample) << 32) | dim);
    return toUnitFloat(h);
}

// A small sequential generator for code that draws many numbers in order.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : state_(mix64(seed)) {}
    std::uint64_t next() { return mix64(state_ += 0x9E3779B97F4A7C15ull); }
    float uniform() { return toUnitFloat(next()); }
    double uniformDouble() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }

private:
    std::uint64_t state_;
};

}  // namespace weft
