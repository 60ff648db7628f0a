// The EXR writer's half conversion: the eight-wide path equals the scalar
// definition on every kind of float, and the definition saturates instead of
// overflowing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/image/io/half_pixels.hpp"

namespace weft {
namespace {

float fromBits(std::uint32_t bits) {
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

TEST(HalfPixels, SaturatesAndZeroesNaN) {
    EXPECT_EQ(float(toHalfSaturated(1e30f)), 65504.0f);
    EXPECT_EQ(float(toHalfSaturated(65520.0f)), 65504.0f);  // would round to Inf
    EXPECT_EQ(float(toHalfSaturated(-std::numeric_limits<float>::infinity())), -65504.0f);
    EXPECT_EQ(toHalfSaturated(std::numeric_limits<float>::quiet_NaN()).bits(), 0u);
    EXPECT_EQ(float(toHalfSaturated(0.1f)), float(Imath::half(0.1f)));
    EXPECT_GT(float(toHalfSaturated(1e-7f)), 0.0f);  // a half denormal, not 0
}

TEST(HalfPixels, EightWidePathEqualsTheDefinitionOnEveryKindOfFloat) {
    // Every 4093rd bit pattern (normals, denormals, Infs, NaNs of both signs)
    // and the half rounding boundaries around 1 and 65504; an odd count so the tail runs too.
    std::vector<float> in;
    for (std::uint64_t bits = 0; bits <= 0xffffffffull; bits += 4093) in.push_back(fromBits(std::uint32_t(bits)));
    for (float base : {1.0f, 65504.0f, 6.1035156e-05f, 5.9604645e-08f})
        for (int k = -64; k <= 64; ++k) in.push_back(std::nextafter(base, k < 0 ? 0.0f : 1e9f) + float(k) * base * 1e-4f);
    for (int m = 0; m < 64; ++m) in.push_back(1.0f + float(2 * m + 1) * std::ldexp(1.0f, -11));  // exact ties
    in.push_back(-0.0f);
    if (in.size() % 8 == 0) in.push_back(3.0f);
    std::vector<Imath::half> fast(in.size());
    toHalfSaturated(in.data(), in.size(), fast.data());
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < in.size(); ++i)
        if (fast[i].bits() != toHalfSaturated(in[i]).bits() && ++mismatches < 5)
            ADD_FAILURE() << "value " << in[i] << ": " << fast[i].bits() << " vs " << toHalfSaturated(in[i]).bits();
    EXPECT_EQ(mismatches, 0u) << "of " << in.size();
}

}  // namespace
}  // namespace weft
