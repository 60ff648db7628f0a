// Edge-avoiding A-Trous: with every range term off it is the plain B3
// a-trous smoothing (checked against a separable reference and the closed
// form of its impulse response), it keeps constant images, it does not blur
// across normal edges, and nothing it writes is NaN/Inf whatever the guides.
#include "core/screen/atrous.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "core/base/error.hpp"
#include "core/base/rng.hpp"

using namespace weft;

namespace {

std::vector<float> randomColor(int w, int h, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<float> c(std::size_t(3) * w * h);
    for (float& v : c) v = rng.uniform() * 4.0f;
    return c;
}

GeometryGuides randomGuides(int w, int h, std::uint64_t seed) {
    Rng rng(seed);
    GeometryGuides g{w, h, {}, {}};
    g.normal.resize(std::size_t(w) * h), g.position.resize(std::size_t(w) * h);
    for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
        g.normal.set(i, rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform());
        g.position.set(i, rng.uniform(), rng.uniform(), rng.uniform() * 3);
    }
    return g;
}

// One 1D pass of the dilated B3 kernel along x or y, out-of-image taps left
// out and the rest renormalised (the 2D filter's border rule, which is
// separable on a rectangle).
std::vector<double> pass1d(const std::vector<double>& in, int w, int h, int step, bool alongX) {
    std::vector<double> out(in.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0, wsum = 0;
                for (int k = -2; k <= 2; ++k) {
                    const int qx = alongX ? x + k * step : x, qy = alongX ? y : y + k * step;
                    if (qx < 0 || qx >= w || qy < 0 || qy >= h) continue;
                    sum += kB3Taps[k + 2] * in[(std::size_t(qy) * w + qx) * 3 + c];
                    wsum += kB3Taps[k + 2];
                }
                out[(std::size_t(y) * w + x) * 3 + c] = sum / wsum;
            }
    return out;
}

bool allFinite(const std::vector<float>& v) {
    for (float x : v)
        if (!std::isfinite(x)) return false;
    return true;
}

}  // namespace

TEST(Atrous, InfiniteSigmasGiveThePlainB3Smoothing) {
    const int w = 37, h = 23;
    const std::vector<float> input = randomColor(w, h, 1);
    std::vector<double> ref(input.begin(), input.end());
    for (int level = 0; level < 4; ++level) ref = pass1d(pass1d(ref, w, h, 1 << level, true), w, h, 1 << level, false);
    std::vector<float> got = input;
    AtrousSettings s;
    s.levels = 4;
    atrousFilter(got, w, h, randomGuides(w, h, 2), s);  // guides present but every term off
    for (std::size_t i = 0; i < got.size(); ++i) ASSERT_NEAR(got[i], ref[i], 1e-5) << i;
}

TEST(Atrous, ImpulseResponseIsTheProductOfDilatedSplines) {
    // Far from the borders, three levels of a unit impulse give K(dx) K(dy),
    // K the convolution of the B3 taps dilated by 1, 2 and 4.
    const int n = 64, c = 32;
    std::vector<double> k(1, 1.0);
    for (int step : {1, 2, 4}) {
        std::vector<double> next(k.size() + 4 * step, 0.0);
        for (std::size_t i = 0; i < k.size(); ++i)
            for (int t = 0; t < 5; ++t) next[i + t * step] += k[i] * kB3Taps[t];
        k = next;
    }
    const int radius = int(k.size() / 2);  // 14
    std::vector<float> img(std::size_t(3) * n * n, 0.0f);
    img[(std::size_t(c) * n + c) * 3 + 1] = 1.0f;
    AtrousSettings s;
    s.levels = 3;
    atrousFilter(img, n, n, GeometryGuides{n, n, {}, {}}, s);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const int dx = x - c, dy = y - c;
            const double expected = std::abs(dx) <= radius && std::abs(dy) <= radius ? k[dx + radius] * k[dy + radius] : 0.0;
            ASSERT_NEAR(img[(std::size_t(y) * n + x) * 3 + 1], expected, 1e-7) << x << "," << y;
            ASSERT_EQ(img[(std::size_t(y) * n + x) * 3], 0.0f);
        }
}

TEST(Atrous, ConstantImageIsKeptWhateverTheGuides) {
    const int w = 29, h = 31;
    GeometryGuides g = randomGuides(w, h, 3);
    for (std::size_t i = 0; i < std::size_t(w) * h; i += 7) g.normal.set(i, 0, 0, 0);  // background
    std::vector<float> img(std::size_t(3) * w * h);
    for (std::size_t i = 0; i < img.size(); ++i) img[i] = i % 3 == 0 ? 0.25f : i % 3 == 1 ? 2.0f : 7.5f;
    AtrousSettings s;
    s.levels = 6, s.sigmaColor = 0.1f, s.sigmaNormal = 0.2f, s.sigmaPosition = 0.05f, s.colorDecay = 0.5f;
    atrousFilter(img, w, h, g, s);
    for (std::size_t i = 0; i < img.size(); ++i) ASSERT_NEAR(img[i], i % 3 == 0 ? 0.25f : i % 3 == 1 ? 2.0f : 7.5f, 1e-5);
}

TEST(Atrous, DoesNotBlurAcrossANormalEdge) {
    // Left half faces +x with value 1, right half faces +y with value 5, noise on top;
    // a strict normal sigma keeps each side's mean.
    const int w = 40, h = 20;
    GeometryGuides g{w, h, {}, {}};
    g.normal.resize(std::size_t(w) * h);
    std::vector<float> img = randomColor(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            if (x < w / 2) g.normal.set(i, 1, 0, 0);
            else g.normal.set(i, 0, 1, 0);
            for (int c = 0; c < 3; ++c) img[3 * i + c] = (x < w / 2 ? 1.0f : 5.0f) + 0.2f * (img[3 * i + c] - 2.0f);
        }
    AtrousSettings s;
    s.levels = 4, s.sigmaNormal = 0.1f;
    atrousFilter(img, w, h, g, s);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float v = img[(std::size_t(y) * w + x) * 3];
            if (x < w / 2) ASSERT_NEAR(v, 1.0f, 0.25f) << x;
            else ASSERT_NEAR(v, 5.0f, 0.25f) << x;
        }
}

TEST(Atrous, NoNanFromZeroNormalsBackgroundOrBadSamples) {
    const int w = 24, h = 18;
    GeometryGuides g = randomGuides(w, h, 5);
    std::vector<float> img = randomColor(w, h, 6);
    const float inf = std::numeric_limits<float>::infinity(), nan = std::nanf("");
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w / 3; ++x) g.normal.set(std::size_t(y) * w + x, 0, 0, 0);  // background band
    g.position.set(5, inf, 0, 0), g.position.set(6, nan, nan, nan), g.normal.set(7, nan, 0, 0);
    g.position.set(8, -inf, inf, 0);
    img[3 * 40] = nan, img[3 * 41 + 1] = inf, img[3 * 42 + 2] = -inf;
    // A block of missing samples larger than the first level reaches: filled later or left 0.
    for (int y = 10; y < 16; ++y)
        for (int x = 10; x < 16; ++x) img[3 * (std::size_t(y) * w + x)] = nan;
    for (float sigma : {1e-20f, 1e-3f, 1.0f, 1e20f}) {
        std::vector<float> out = img;
        AtrousSettings s;
        s.levels = 5, s.sigmaColor = sigma, s.sigmaNormal = sigma, s.sigmaPosition = sigma, s.colorDecay = 0.5f;
        atrousFilter(out, w, h, g, s);
        EXPECT_TRUE(allFinite(out)) << "sigma " << sigma;
    }
    std::vector<float> allNan(std::size_t(3) * w * h, nan);
    atrousFilter(allNan, w, h, g, AtrousSettings{});
    for (float v : allNan) ASSERT_EQ(v, 0.0f);  // no sample anywhere: 0, not NaN
}

TEST(Atrous, SameResultOnAnyThreadCount) {
    const int w = 61, h = 47;
    const GeometryGuides g = randomGuides(w, h, 7);
    AtrousSettings s;
    s.levels = 5, s.sigmaColor = 0.8f, s.sigmaNormal = 0.3f, s.sigmaPosition = 0.4f;
    std::vector<float> one = randomColor(w, h, 8), two = one;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        atrousFilter(one, w, h, g, s);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        atrousFilter(two, w, h, g, s);
    }
    EXPECT_EQ(one, two);
}

TEST(Atrous, ImageFilterNamesMissingGuideChannels) {
    Image img(8, 8, {"R", "G", "B", "A", "indirect.R", "indirect.G", "indirect.B", "N.X", "N.Y", "N.Z"});
    AtrousSettings s;
    s.sigmaNormal = 0.5f, s.sigmaPosition = 0.1f;
    try {
        atrousFilterImage(img, "indirect", "N", "P", s);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("P.X, P.Y, P.Z"), std::string::npos) << e.what();
    }
    s.sigmaPosition = AtrousSettings::kOff;
    img.at(3, 3, img.channelIndex("indirect.G")) = 16.0f;
    img.at(3, 3, 0) = 2.0f;
    atrousFilterImage(img, "indirect", "N", "P", s);  // normals all zero: equal, so plain smoothing
    EXPECT_LT(img.at(3, 3, img.channelIndex("indirect.G")), 16.0f);
    EXPECT_GT(img.at(4, 3, img.channelIndex("indirect.G")), 0.0f);
    EXPECT_EQ(img.at(3, 3, 0), 2.0f);  // other layers untouched
    EXPECT_THROW(atrousFilterImage(img, "nothing", "N", "P", s), Error);
}

TEST(Atrous, RejectsBadSettings) {
    std::vector<float> img(3 * 4, 0.0f);
    AtrousSettings s;
    s.sigmaNormal = 0;
    EXPECT_THROW(atrousFilter(img, 2, 2, GeometryGuides{2, 2, {}, {}}, s), Error);
    s = AtrousSettings{};
    s.levels = -1;
    EXPECT_THROW(atrousFilter(img, 2, 2, GeometryGuides{2, 2, {}, {}}, s), Error);
    s = AtrousSettings{};
    s.sigmaNormal = 1;  // normals needed but not given
    EXPECT_THROW(atrousFilter(img, 2, 2, GeometryGuides{2, 2, {}, {}}, s), Error);
}
