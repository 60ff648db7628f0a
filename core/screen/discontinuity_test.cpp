// The discontinuity buffer on synthetic G-buffers, and the blur that must
// not cross what it marks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "core/base/memory/large_buffer.hpp"
#include "core/screen/discontinuity.hpp"
#include "core/base/rng.hpp"

using namespace weft;

namespace {

// A w x h G-buffer of a plane z = 0 seen from z = 10, normal +z.
GBuffer plane(int w, int h) {
    GBuffer g;
    g.width = w, g.height = h;
    g.texels.resize(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            GTexel& t = g.at(x, y);
            t.position = Vec3f(float(x) * 0.01f, float(y) * 0.01f, 0);
            t.normal = Vec3f(0, 0, 1), t.depth = 10, t.material = 0, t.front = true;
        }
    return g;
}

}  // namespace

TEST(Discontinuity, NormalStepMarksTheColumnBeforeIt) {
    GBuffer g = plane(8, 5);
    for (int y = 0; y < 5; ++y)
        for (int x = 4; x < 8; ++x) g.at(x, y).normal = Vec3f(1, 0, 0);
    const auto d = discontinuityBuffer(g, {});
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 8; ++x) EXPECT_EQ(d[std::size_t(y) * 8 + x], x == 3 ? 1 : 0) << x << "," << y;
}

TEST(Discontinuity, DepthStepAndDiagonalAndBackground) {
    GBuffer g = plane(6, 6);
    g.at(5, 5).position += Vec3f(0, 0, 2);  // far behind: only its upper-left diagonal neighbour sees it... and its left/top ones
    auto d = discontinuityBuffer(g, {0.9f, 0.05f});
    EXPECT_EQ(d[4 * 6 + 4], 1);  // (4,4): diagonal neighbour (5,5) differs
    EXPECT_EQ(d[5 * 6 + 4], 1);  // (4,5): +x neighbour
    EXPECT_EQ(d[4 * 6 + 5], 1);  // (5,4): +y neighbour
    EXPECT_EQ(d[5 * 6 + 5], 0);  // no positive neighbours inside the image
    EXPECT_EQ(d[3 * 6 + 3], 0);
    // A looser threshold accepts the same step.
    d = discontinuityBuffer(g, {0.9f, 0.5f});
    EXPECT_EQ(d[4 * 6 + 4], 0);
    g.at(0, 1).material = -1;  // background next to surface
    d = discontinuityBuffer(g, {});
    EXPECT_EQ(d[0], 1);
    EXPECT_EQ(d[1 * 6 + 0], 1);
}

TEST(Discontinuity, BlurKeepsConstantsAndDoesNotCrossEdges) {
    const int w = 16, h = 8;
    GBuffer g = plane(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 8; x < w; ++x) g.at(x, y).normal = Vec3f(1, 0, 0);
    const auto disc = discontinuityBuffer(g, {});
    std::vector<float> data(std::size_t(w) * h * 2);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) data[(std::size_t(y) * w + x) * 2] = x < 8 ? 0.0f : 1.0f, data[(std::size_t(y) * w + x) * 2 + 1] = 3.0f;
    discontinuityBlur(data, w, h, 2, disc, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            EXPECT_FLOAT_EQ(data[(std::size_t(y) * w + x) * 2], x < 8 ? 0.0f : 1.0f) << x << "," << y;
            EXPECT_NEAR(data[(std::size_t(y) * w + x) * 2 + 1], 3.0f, 1e-5f);
        }
}

TEST(Discontinuity, BlurIgnoresWhatItsScratchHeldAndLeavesOtherChannels) {
    // Large enough that the blur's scratch comes from a released buffer's
    // mapping: a buffer of its size filled with NaN is released first.
    const int w = 512, h = 256, stride = 3, channels = 2;
    GBuffer g = plane(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if ((x * 7 + y * 3) % 11 == 0) g.at(x, y).normal = Vec3f(0, 1, 0);
    const auto disc = discontinuityBuffer(g, {});
    std::vector<float> data(std::size_t(w) * h * stride);
    Rng rng(11);
    for (float& v : data) v = rng.uniform();
    std::vector<float> first = data, second = data;
    discontinuityBlur(first.data(), w, h, stride, channels, disc, 4);
    { const FreshBuffer<float> poison = filledBuffer(std::size_t(w) * h * channels, std::numeric_limits<float>::quiet_NaN()); }
    discontinuityBlur(second.data(), w, h, stride, channels, disc, 4);
    EXPECT_TRUE(lastLargePagesReused()) << "the second blur's scratch should reuse the NaN buffer's pages";
    for (std::size_t i = 0; i < data.size(); ++i) {
        ASSERT_EQ(second[i], first[i]) << i;
        if (i % stride == 2) {
            ASSERT_EQ(second[i], data[i]) << "channel 3 is not blurred, " << i;
        }
    }
    EXPECT_NE(first, data);
}

TEST(Discontinuity, BlurReducesNoiseInsideARegion) {
    const int w = 32, h = 32;
    const GBuffer g = plane(w, h);
    const auto disc = discontinuityBuffer(g, {});
    std::vector<float> data(std::size_t(w) * h);
    Rng rng(7);
    for (float& v : data) v = rng.uniform();
    auto variance = [&] {
        double s = 0, s2 = 0;
        for (float v : data) s += v, s2 += double(v) * v;
        const double mean = s / double(data.size());
        return s2 / double(data.size()) - mean * mean;
    };
    const double before = variance();
    discontinuityBlur(data, w, h, 1, disc, 2);
    EXPECT_LT(variance(), before / 4);
}

namespace {

// The blur as section 4.5 reads: from each pixel, walk +1, +2, ... then
// -1, -2, ... up to the radius, a step from q to q + 1 only when q is
// not marked; Gaussian weights, normalised by those taken. Along x, then y.
void walkedBlur(std::vector<float>& data, int w, int h, int stride, int channels, const std::vector<std::uint8_t>& disc, int radius) {
    const float sigma = 0.5f * float(radius);
    std::vector<float> weight(std::size_t(radius) + 1);
    for (int k = 0; k <= radius; ++k) weight[std::size_t(k)] = std::exp(-0.5f * float(k * k) / (sigma * sigma));
    for (bool alongX : {true, false}) {
        const std::vector<float> src = data;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const int pos = alongX ? x : y, len = alongX ? w : h;
                auto index = [&](int q) { return alongX ? std::size_t(y) * w + q : std::size_t(q) * w + x; };
                std::vector<float> acc(static_cast<std::size_t>(channels), 0.0f);
                float wsum = weight[0];
                for (int c = 0; c < channels; ++c) acc[c] = weight[0] * src[index(pos) * stride + c];
                auto add = [&](int q, float wk) {
                    wsum += wk;
                    for (int c = 0; c < channels; ++c) acc[c] += wk * src[index(q) * stride + c];
                };
                for (int k = 1; k <= radius && pos + k < len && !disc[index(pos + k - 1)]; ++k) add(pos + k, weight[std::size_t(k)]);
                for (int k = 1; k <= radius && pos - k >= 0 && !disc[index(pos - k)]; ++k) add(pos - k, weight[std::size_t(k)]);
                for (int c = 0; c < channels; ++c) data[index(pos) * stride + c] = acc[c] * (1.0f / wsum);
            }
    }
}

}  // namespace

// Pixels far from marks take a vectorised plain Gaussian over runs of
// pixels; it must give the walk's result to the bit, next to marks, at the
// borders and across channel counts, strides and radii.
TEST(Discontinuity, BlurEqualsTheWalkToTheBit) {
    const int w = 61, h = 47;
    GBuffer g = plane(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if ((x > 30 && (x * 13 + y * 7) % 37 == 0) || (y == 20 && x < 12)) g.at(x, y).normal = Vec3f(0, 1, 0);
    const auto disc = discontinuityBuffer(g, {});
    for (const auto& [stride, channels] : {std::pair{12, 6}, std::pair{12, 12}, std::pair{6, 6}, std::pair{3, 2}, std::pair{1, 1}})
        for (int radius : {1, 4, 8, 40}) {
            std::vector<float> data(std::size_t(w) * h * stride);
            Rng rng(std::uint64_t(radius * 100 + stride));
            for (float& v : data) v = rng.uniform();
            std::vector<float> walked = data;
            discontinuityBlur(data.data(), w, h, stride, channels, disc, radius);
            walkedBlur(walked, w, h, stride, channels, disc, radius);
            int differ = 0;
            for (std::size_t i = 0; i < data.size(); ++i) differ += data[i] != walked[i];
            EXPECT_EQ(differ, 0) << "stride " << stride << " channels " << channels << " radius " << radius;
        }
}
