// PixelSampler: values as pure functions of (seed, pixel, sample, dimension)
// as the definition states them (a Kensler permutation of the strata keyed
// by the pixel and dimension, jittered by pixelRandom), each dimension a
// Latin hypercube over the pixel's samples, and uniform (chi-square).
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "core/sampling/pixel_sampler.hpp"

using namespace weft;

namespace {

// The definition, hashed from scratch on every call.
float definition(std::uint64_t seed, int x, int y, std::uint32_t sample, std::uint32_t count, std::uint32_t dim) {
    const auto key = std::uint32_t(hashCombine(hashCombine(seed, (std::uint64_t(std::uint32_t(x)) << 32) | std::uint32_t(y)), dim));
    const std::uint32_t stratum = permuteIndex(sample % count, count, key);
    const float u = (float(stratum) + pixelRandom(seed ^ 0x5bd1e995ull, x, y, sample, dim)) / float(count);
    return u < 1.0f ? u : 0x1.fffffep-1f;
}

}  // namespace

TEST(PixelSampler, ValuesAreTheDefinitionBitForBit) {
    Rng rng(3);
    for (int trial = 0; trial < 20000; ++trial) {
        const std::uint64_t seed = rng.next();
        const int x = int(rng.next() % 5000) - 100, y = int(rng.next() % 5000) - 100;
        const std::uint32_t count = 1 + std::uint32_t(rng.next() % 300), sample = std::uint32_t(rng.next() % 1000);
        const std::uint32_t dim = std::uint32_t(rng.next() % 64) + (trial % 7 == 0 ? kShutterDim : 0);
        ASSERT_EQ(PixelSampler(seed, x, y, sample, count).get(dim), definition(seed, x, y, sample, count, dim)) << trial;
    }
}

TEST(PixelSampler, EachDimensionIsALatinHypercube) {
    for (const std::uint32_t count : {1u, 7u, 64u, 250u})
        for (std::uint32_t dim = 0; dim < 6; ++dim) {
            std::vector<int> strata;
            for (std::uint32_t k = 0; k < count; ++k) {
                const float u = PixelSampler(42, 3, 9, k, count).get(dim);
                ASSERT_GE(u, 0.0f);
                ASSERT_LT(u, 1.0f);
                strata.push_back(int(u * float(count)));
            }
            std::sort(strata.begin(), strata.end());
            for (std::uint32_t k = 0; k < count; ++k) EXPECT_EQ(strata[k], int(k)) << count << " " << dim;
        }
}

// One sample per pixel over many pixels: 20 bins, chi-square with 19
// degrees of freedom below its 0.999 quantile (43.8), seed fixed.
TEST(PixelSampler, OneSamplePerPixelIsUniform) {
    std::vector<int> bins(20, 0);
    const int n = 200000;
    for (int i = 0; i < n; ++i) ++bins[std::size_t(PixelSampler(7, i % 1000, i / 1000, 0, 1).get(2) * 20)];
    double chi2 = 0;
    for (int b : bins) chi2 += (b - n / 20.0) * (b - n / 20.0) / (n / 20.0);
    EXPECT_LT(chi2, 43.8);
}
