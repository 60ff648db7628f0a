// LDR-FLIP: bounds, zero for equal images, growth with noise, locality, errors.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "core/base/error.hpp"
#include "core/base/rng.hpp"
#include "core/image/compare/flip.hpp"
#include "tests/support/test_support.hpp"

#include <tbb/task_arena.h>

using namespace weft;

namespace {

Image filled(int w, int h, float r, float g, float b) {
    Image img = Image::rgba(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img.at(x, y, 0) = r, img.at(x, y, 1) = g, img.at(x, y, 2) = b, img.at(x, y, 3) = 1;
    return img;
}

// Uniform random R, G, B in [lo, hi), alpha 1.
Image randomImage(int w, int h, std::uint64_t seed, float lo = 0, float hi = 1) {
    Image img = filled(w, h, 0, 0, 0);
    Rng rng(seed);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = lo + (hi - lo) * rng.uniform();
    return img;
}

// A smooth colour ramp with a bright square: edges and flat regions.
Image scene(int w, int h) {
    Image img = filled(w, h, 0, 0, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool square = x > w / 4 && x < w / 2 && y > h / 4 && y < h / 2;
            img.at(x, y, 0) = 0.2f + 0.6f * x / w;
            img.at(x, y, 1) = square ? 0.8f : 0.3f;
            img.at(x, y, 2) = 0.2f + 0.6f * y / h;
        }
    return img;
}

// base + amplitude * the same uniform noise in [-1, 1) (seed fixed), so
// only the amplitude changes between calls.
Image withNoise(const Image& base, float amplitude) {
    Image img = base;
    Rng rng(42);
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) += amplitude * (2 * rng.uniform() - 1);
    return img;
}

std::string errorOf(const Image& a, const Image& b, double ppd = 67) {
    try {
        flipError(a, b, ppd);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Flip, IdenticalImagesGiveZero) {
    const Image img = randomImage(40, 30, 1);
    const FlipResult r = flipError(img, img);
    EXPECT_EQ(r.mean, 0.0);
    ASSERT_EQ(r.errorMap.width(), 40);
    ASSERT_EQ(r.errorMap.height(), 30);
    ASSERT_EQ(r.errorMap.channelNames(), std::vector<std::string>{"FLIP"});
    for (float v : r.errorMap.data()) EXPECT_EQ(v, 0.0f);
}

// Includes values outside [0, 1], which are clamped like a display would.
TEST(Flip, RandomImagesStayInUnitRange) {
    for (std::uint64_t seed = 0; seed < 6; ++seed) {
        const Image a = randomImage(32, 24, 2 * seed, -0.5f, 1.5f), b = randomImage(32, 24, 2 * seed + 1, -0.5f, 1.5f);
        const FlipResult r = flipError(a, b);
        double sum = 0;
        for (float v : r.errorMap.data()) {
            ASSERT_GE(v, 0.0f);
            ASSERT_LE(v, 1.0f);
            sum += v;
        }
        EXPECT_GT(r.mean, 0.05);
        EXPECT_NEAR(r.mean, sum / (32 * 24), 1e-9);
    }
}

TEST(Flip, NonFiniteInputsStayInUnitRange) {
    Image a = randomImage(16, 16, 5);
    a.at(3, 3, 0) = std::numeric_limits<float>::quiet_NaN();
    a.at(8, 8, 1) = std::numeric_limits<float>::infinity();
    const FlipResult r = flipError(a, randomImage(16, 16, 6));
    for (float v : r.errorMap.data()) ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
}

TEST(Flip, MeanGrowsWithNoiseAmplitude) {
    const Image base = scene(64, 48);
    double previous = 0;
    for (float amplitude : {0.02f, 0.05f, 0.1f, 0.2f}) {
        const double m = flipError(withNoise(base, amplitude), base).mean;
        EXPECT_GT(m, previous) << "amplitude " << amplitude;
        previous = m;
    }
    EXPECT_LT(previous, 0.9);  // noise of 0.2 is far from black vs white
}

// Flat images: no features, so the error is the colour term alone. By hand:
// HyAB(black, white) = 100 (L only), 100^0.7 = 25.119; the maximum, green vs
// blue after the Hunt adjustment, is HyAB = 203.297, 203.297^0.7 = 41.275;
// above p_c * 41.275 the remap gives 0.95 + (25.119 - 16.510) / 24.765 * 0.05.
TEST(Flip, BlackVersusWhiteIsNearOne) {
    const FlipResult r = flipError(filled(20, 20, 0, 0, 0), filled(20, 20, 1, 1, 1));
    EXPECT_GT(r.mean, 0.9);
    EXPECT_NEAR(r.mean, 0.96738, 1e-4);
}

TEST(Flip, GreenVersusBlueIsTheMaximum) {
    EXPECT_NEAR(flipError(filled(8, 8, 0, 1, 0), filled(8, 8, 0, 0, 1)).mean, 1.0, 1e-5);
}

// The colour error of flat images (no features, and a normalised CSF
// leaves a flat colour as it is) by its definition, in double precision
// with the library's cbrt and pow: Hunt-adjusted CIELAB, HyAB, the power
// q_c and the remap (the paper's constants). FLIP's float loops (their own
// cube root and power) must agree over the colour cube, dark to saturated.
double colourErrorByDefinition(const std::array<double, 3>& p, const std::array<double, 3>& q) {
    const double m[3][3] = {{0.4124564, 0.3575761, 0.1804375}, {0.2126729, 0.7151522, 0.0721750}, {0.0193339, 0.1191920, 0.9503041}};
    const auto lab = [&](const std::array<double, 3>& rgb) {
        double f[3];
        for (int i = 0; i < 3; ++i) {
            const double white = m[i][0] + m[i][1] + m[i][2], t = (m[i][0] * rgb[0] + m[i][1] * rgb[1] + m[i][2] * rgb[2]) / white;
            const double d = 6.0 / 29;
            f[i] = t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29;
        }
        const double L = 116 * f[1] - 16;
        return std::array<double, 3>{L, 0.01 * L * 500 * (f[0] - f[1]), 0.01 * L * 200 * (f[1] - f[2])};
    };
    const auto hyab = [&](const std::array<double, 3>& a, const std::array<double, 3>& b) {
        const std::array<double, 3> x = lab(a), y = lab(b);
        return std::abs(x[0] - y[0]) + std::hypot(x[1] - y[1], x[2] - y[2]);
    };
    const double cmax = std::pow(hyab({0, 1, 0}, {0, 0, 1}), 0.7), e = std::pow(hyab(p, q), 0.7);
    return e < 0.4 * cmax ? 0.95 / (0.4 * cmax) * e : 0.95 + (e - 0.4 * cmax) / (0.6 * cmax) * 0.05;
}

TEST(Flip, FlatColoursGiveTheColourErrorOfTheDefinition) {
    Rng rng(2026);
    for (int k = 0; k < 200; ++k) {
        std::array<double, 3> p, q;
        for (int c = 0; c < 3; ++c) p[c] = rng.uniform(), q[c] = k % 4 == 0 ? p[c] * 0.9 : rng.uniform();  // near and far pairs
        if (k % 10 == 1) p = {0.002, 0.001, 0.003};                                                        // below the cube root's knee
        const double expected = colourErrorByDefinition(p, q);
        const double got = flipError(filled(4, 4, float(p[0]), float(p[1]), float(p[2])), filled(4, 4, float(q[0]), float(q[1]), float(q[2]))).mean;
        EXPECT_NEAR(got, expected, 2e-4 * (1 + expected)) << k;  // float colour pipeline: 1e-4 at most here
    }
}

// LDR-FLIP treats both images alike (the feature term compares magnitudes
// with |.|, HyAB is a distance), so a swap gives the same values exactly.
TEST(Flip, SwappingTheImagesGivesTheSameError) {
    const Image a = withNoise(scene(48, 40), 0.1f), b = scene(48, 40);
    const FlipResult ab = flipError(a, b), ba = flipError(b, a);
    EXPECT_GT(ab.mean, 0.0);
    EXPECT_EQ(ab.mean, ba.mean);
    EXPECT_EQ(ab.errorMap.data(), ba.errorMap.data());
}

// A one-pixel change only reaches as far as the filters do (about 10 px at
// 67 pixels per degree); seen from farther away (more pixels per degree)
// the same change is smaller and less visible.
TEST(Flip, SinglePixelChangeIsLocal) {
    const Image ref = filled(64, 64, 0.5f, 0.5f, 0.5f);
    Image test = ref;
    test.at(10, 10, 0) = test.at(10, 10, 1) = test.at(10, 10, 2) = 1.0f;
    const FlipResult r = flipError(test, ref);
    EXPECT_GT(r.errorMap.at(10, 10, 0), 0.1f);
    EXPECT_EQ(r.errorMap.at(40, 40, 0), 0.0f);
    EXPECT_EQ(r.errorMap.at(10, 40, 0), 0.0f);
    EXPECT_LT(flipError(test, ref, 200).errorMap.at(10, 10, 0), r.errorMap.at(10, 10, 0));
}

TEST(Flip, AlphaAndOtherChannelsAreIgnored) {
    Image a = scene(24, 24), b = withNoise(scene(24, 24), 0.05f);
    const double before = flipError(a, b).mean;
    a.addChannel("Z");
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) a.at(x, y, 3) = 0.25f, a.at(x, y, 4) = 7.0f;
    EXPECT_EQ(flipError(a, b).mean, before);
}

TEST(Flip, ErrorsAreOneLine) {
    const std::string size = errorOf(filled(8, 8, 0, 0, 0), filled(8, 9, 0, 0, 0));
    EXPECT_NE(size.find("8x8 vs 8x9"), std::string::npos) << size;
    Image noBlue(8, 8, {"R", "G", "A"});
    const std::string channel = errorOf(filled(8, 8, 0, 0, 0), noBlue);
    EXPECT_NE(channel.find("reference image has no B channel"), std::string::npos) << channel;
    EXPECT_NE(errorOf(noBlue, noBlue).find("test image"), std::string::npos);
    EXPECT_NE(errorOf(filled(4, 4, 0, 0, 0), filled(4, 4, 0, 0, 0), 0).find("pixels per degree"), std::string::npos);
    EXPECT_NE(errorOf(filled(4, 4, 0, 0, 0), filled(4, 4, 0, 0, 0), NAN).find("pixels per degree"), std::string::npos);
    for (const std::string& m : {size, channel}) EXPECT_EQ(m.find('\n'), std::string::npos);
}

TEST(Flip, EmptyImagesGiveZero) {
    const FlipResult r = flipError(Image::rgba(0, 0), Image::rgba(0, 0));
    EXPECT_EQ(r.mean, 0.0);
    EXPECT_TRUE(r.errorMap.data().empty());
}

// A prepared reference gives flipError's map and mean for every test image
// compared with it, and the same on one thread as on four.
TEST(Flip, PreparedReferenceGivesTheSameMapOnAnyThreadCount) {
    const Image reference = scene(61, 37);
    const FlipReference prepared(reference);
    for (float amplitude : {0.0f, 0.05f, 0.4f}) {
        const Image test = withNoise(reference, amplitude);
        const FlipResult once = flipError(test, reference);
        FlipResult one, four;
        tbb::task_arena(1).execute([&] { one = prepared.compare(test); });
        tbb::task_arena(4).execute([&] { four = prepared.compare(test); });
        for (const FlipResult* r : {&one, &four}) {
            EXPECT_EQ(r->mean, once.mean) << amplitude;
            EXPECT_EQ(r->errorMap.data(), once.errorMap.data()) << amplitude;
        }
    }
    EXPECT_NE(test::errorOf([&] { prepared.compare(scene(61, 36)); }).find("61x36 vs 61x37"), std::string::npos);
}
