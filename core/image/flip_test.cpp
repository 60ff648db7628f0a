// LDR-FLIP: bounds, zero for equal images, growth with noise, locality, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/base/error.hpp"
#include "core/base/rng.hpp"
#include "core/image/flip.hpp"
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
