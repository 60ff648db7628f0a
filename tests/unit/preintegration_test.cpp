#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/base/error.hpp"
#include "core/volume/optics/preintegration.hpp"
#include "core/volume/volume_ray.hpp"
#include "tests/support/transfer_functions.hpp"

using namespace weft;

namespace {

// The default smoke-like ramp: smooth, modest extinction.
TransferFunction smoothTf() {
    return TransferFunction(0, 1, {{0.0, {0.35, 0.45, 0.65}, 0.0},
                                   {0.15, {0.75, 0.75, 0.8}, 0.08},
                                   {1.0, {1.0, 0.85, 0.65}, 0.6}});
}

using test::peakedTf;

TransferFunction constantTf(double extinction, std::array<double, 3> color = {0.9, 0.5, 0.2}) {
    return TransferFunction(0, 1, {{0.0, color, extinction}, {1.0, color, extinction}});
}

struct Exact {
    std::array<double, 3> c{0, 0, 0};
    double a = 0;
};

// Brute force: the segment in tiny steps, each at constant scalar (its
// midpoint) composited front to back. The scalar range is first cut at the
// transfer function's points so no step straddles a kink or a step, which
// would otherwise dominate the error.
Exact bruteForce(const TransferFunction& tf, double sFront, double sBack, double length, int stepsPerPiece) {
    const double lo = std::min(sFront, sBack), hi = std::max(sFront, sBack);
    std::vector<double> cuts{sFront, sBack};
    for (const TfPoint& p : tf.points())
        if (p.s > lo && p.s < hi) cuts.push_back(p.s);
    std::sort(cuts.begin(), cuts.end());
    if (sFront > sBack) std::reverse(cuts.begin(), cuts.end());
    Exact out;
    double depth = 0;
    for (size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double s0 = cuts[k], s1 = cuts[k + 1];
        const double dx = hi > lo ? length * std::abs(s1 - s0) / (hi - lo) : length;
        for (int i = 0; i < stepsPerPiece; ++i) {
            const TfPoint p = tf.atS(s0 + (s1 - s0) * (i + 0.5) / stepsPerPiece);
            const double stepDepth = p.extinction * dx / stepsPerPiece;
            const double w = std::exp(-depth) * -std::expm1(-stepDepth);
            for (int c = 0; c < 3; ++c) out.c[c] += w * p.color[c];
            depth += stepDepth;
        }
    }
    out.a = -std::expm1(-depth);
    return out;
}

std::array<double, 4> channels(const PreintSample& s) { return {s.r, s.g, s.b, s.a}; }
std::array<double, 4> channels(const Exact& e) { return {e.c[0], e.c[1], e.c[2], e.a}; }

bool finiteSample(const PreintSample& s) {
    return std::isfinite(s.r) && std::isfinite(s.g) && std::isfinite(s.b) && std::isfinite(s.a);
}

// Deterministic uniform [0, 1) from a seeded generator (independent of the library's distributions).
double uniform01(std::mt19937& gen) { return double(gen() >> 8) * 0x1p-24; }

}  // namespace

// Tolerance: |got - brute| <= 2e-7 + 1e-6 |brute| per channel. integrateSegment
// returns floats (half an ulp is 6e-8 at 1); the brute force's own error is
// below 1e-8 on these cases.
TEST(PreintSegment, MatchesBruteForceQuadrature) {
    const std::vector<double> sValues{0.0, 0.2, 0.47, 0.5, 0.62, 0.7, 1.0};
    const std::vector<double> lengths{1e-6, 0.01, 1.0, 4.0, 64.0};
    std::vector<std::pair<double, double>> pairs;
    for (double a : sValues)
        for (double b : sValues) pairs.emplace_back(a, b);
    for (double s : {0.3, 0.5, 0.7})
        pairs.insert(pairs.end(), {{s, s + 1e-9}, {s + 1e-9, s}, {s - 5e-10, s + 5e-10}});
    double maxErr = 0;
    for (const TransferFunction& tf : {smoothTf(), peakedTf()})
        for (const auto& [sf, sb] : pairs)
            for (double len : lengths) {
                const auto got = channels(PreintegrationTable::integrateSegment(tf, sf, sb, len));
                const auto ref = channels(bruteForce(tf, sf, sb, len, 100000));
                for (int c = 0; c < 4; ++c) {
                    maxErr = std::max(maxErr, std::abs(got[c] - ref[c]));
                    ASSERT_NEAR(got[c], ref[c], 2e-7 + 1e-6 * std::abs(ref[c]))
                        << "channel " << c << " s " << sf << " -> " << sb << " length " << len;
                }
            }
    RecordProperty("max_abs_error", std::to_string(maxErr));
    std::printf("[ preint   ] integrateSegment vs brute force: max abs error %.3g\n", maxErr);
}

// Short segments are where relative precision is easily lost (1 - exp(-x) for tiny x).
TEST(PreintSegment, ShortSegmentsKeepRelativePrecision) {
    const TransferFunction tf = peakedTf();
    for (double len : {1e-6, 1e-9})
        for (const auto& [sf, sb] : std::vector<std::pair<double, double>>{{0.2, 0.6}, {0.6, 0.2}, {0.48, 0.52}}) {
            const auto got = channels(PreintegrationTable::integrateSegment(tf, sf, sb, len));
            const auto ref = channels(bruteForce(tf, sf, sb, len, 100000));
            for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], ref[c], 1e-6 * ref[c]) << c << " length " << len;
        }
}

TEST(PreintSegment, ExtremeLengthsAndExtinctionsStayFiniteAndBounded) {
    const std::vector<double> grid{0.0, 0.1, 0.25, 0.5, 0.5 + 1e-9, 0.7, 1.0};
    auto check = [&](const TransferFunction& tf, double len, double maxColor) {
        for (double sf : grid)
            for (double sb : grid) {
                const PreintSample s = PreintegrationTable::integrateSegment(tf, sf, sb, len);
                ASSERT_TRUE(finiteSample(s)) << sf << " " << sb << " " << len;
                ASSERT_GE(s.a, 0.0f);
                ASSERT_LE(s.a, 1.0f);
                for (float c : {s.r, s.g, s.b}) {
                    ASSERT_GE(c, 0.0f);
                    ASSERT_LE(c, maxColor * s.a * (1 + 1e-6f) + 1e-30f);
                }
            }
    };
    for (const auto& tf : {smoothTf(), peakedTf(), constantTf(1e6), constantTf(1e30)})
        for (double len : {1e-12, 1e-6, 1.0, 64.0}) check(tf, len, 1.0f);
    // Extinction ramping from 0 to 1e30 across s: opaque, colour from the thin end.
    const TransferFunction ramp(0, 1, {{0.0, {0.2, 0.4, 0.6}, 0.0}, {1.0, {1.0, 1.0, 1.0}, 1e30}});
    for (double len : {1e-12, 1.0, 64.0}) check(ramp, len, 1.0f);

    const PreintSample opaque = PreintegrationTable::integrateSegment(constantTf(1e30), 0.2, 0.8, 1.0);
    EXPECT_EQ(opaque.a, 1.0f);
    EXPECT_FLOAT_EQ(opaque.r, 0.9f);
    const PreintSample opaqueConst = PreintegrationTable::integrateSegment(constantTf(1e6), 0.4, 0.4, 64.0);
    EXPECT_EQ(opaqueConst.a, 1.0f);
    EXPECT_FLOAT_EQ(opaqueConst.g, 0.5f);
}

TEST(PreintSegment, TinyLengthGivesFirstOrderOpacity) {
    const TransferFunction tf = constantTf(0.75);
    const PreintSample s = PreintegrationTable::integrateSegment(tf, 0.1, 0.9, 1e-12);
    EXPECT_NEAR(s.a, 0.75e-12, 1e-6 * 0.75e-12);
    EXPECT_NEAR(s.r, 0.9 * 0.75e-12, 1e-6 * 0.9 * 0.75e-12);
    const PreintSample zero = PreintegrationTable::integrateSegment(tf, 0.1, 0.9, 0.0);
    EXPECT_EQ(zero.a, 0.0f);
    EXPECT_EQ(zero.r, 0.0f);
}

TEST(PreintSegment, ZeroExtinctionIsTransparentAndDark) {
    const TransferFunction tf(0, 1, {{0.0, {1, 1, 1}, 0.0}, {0.5, {0.3, 0.2, 0.1}, 0.0}, {1.0, {1, 0, 0}, 0.0}});
    for (double sf : {0.0, 0.3, 1.0})
        for (double sb : {0.0, 0.6, 1.0}) {
            const PreintSample s = PreintegrationTable::integrateSegment(tf, sf, sb, 64.0);
            EXPECT_EQ(s.a, 0.0f);
            EXPECT_EQ(s.r, 0.0f);
            EXPECT_EQ(s.g, 0.0f);
            EXPECT_EQ(s.b, 0.0f);
        }
}

TEST(PreintSegment, NanAndOutOfRangeScalarsAreClampedAndBadLengthsRejected) {
    const TransferFunction tf = smoothTf();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const auto clamped = channels(PreintegrationTable::integrateSegment(tf, -3.0, 7.0, 2.0));
    const auto expected = channels(PreintegrationTable::integrateSegment(tf, 0.0, 1.0, 2.0));
    EXPECT_EQ(clamped, expected);
    EXPECT_EQ(channels(PreintegrationTable::integrateSegment(tf, nan, 0.5, 2.0)),
              channels(PreintegrationTable::integrateSegment(tf, 0.0, 0.5, 2.0)));
    EXPECT_THROW(PreintegrationTable::integrateSegment(tf, 0.1, 0.2, -1.0), Error);
    EXPECT_THROW(PreintegrationTable::integrateSegment(tf, 0.1, 0.2, nan), Error);
}

// A constant segment must be what the ray marcher composites, so that
// pre-integrated and plain rendering converge to the same image.
TEST(PreintSegment, ConstantScalarEqualsRayAccumulatorAdd) {
    for (const TransferFunction& tf : {smoothTf(), peakedTf(), constantTf(1e6)})
        for (double s : {0.0, 0.15, 0.33, 0.5, 0.69, 0.7, 1.0})
            for (double len : {1e-6, 0.25, 1.0, 8.0, 64.0}) {
                const TfPoint p = tf.atS(s);
                RayAccumulator acc;
                acc.add({float(p.color[0]), float(p.color[1]), float(p.color[2]), float(p.extinction)},
                        segmentOpacity(float(p.extinction), float(len)));
                const PreintSample got = PreintegrationTable::integrateSegment(tf, s, s, len);
                // Opacity from segmentOpacity itself: acc.opacity() is 1 - (1 - alpha), which loses digits.
                const std::array<double, 4> want{acc.r, acc.g, acc.b, segmentOpacity(float(p.extinction), float(len))};
                for (int c = 0; c < 4; ++c)
                    EXPECT_NEAR(channels(got)[c], want[c], 5e-7 * want[c] + 1e-30) << c << " s " << s << " len " << len;
            }
}

// Scalars a hair apart take the general path; it must meet the closed form.
TEST(PreintSegment, NearlyEqualScalarsMatchConstantCase) {
    for (const TransferFunction& tf : {smoothTf(), peakedTf()})
        for (double s : {0.2, 0.5, 0.6})
            for (double len : {1e-6, 1.0, 64.0}) {
                const auto same = channels(PreintegrationTable::integrateSegment(tf, s, s, len));
                for (double d : {1e-12, -1e-9}) {
                    const auto near = channels(PreintegrationTable::integrateSegment(tf, s, s + d, len));
                    for (int c = 0; c < 4; ++c) EXPECT_NEAR(near[c], same[c], 1e-6 * same[c] + 1e-12);
                }
            }
}

// Splitting a segment at its midpoint scalar and compositing the halves front
// to back gives the whole: a property of the exact integral, not of the table.
TEST(PreintSegment, HalvesCompositeToWholeSegment) {
    for (const TransferFunction& tf : {smoothTf(), peakedTf()})
        for (double sf : {0.0, 0.3, 0.5, 0.65, 1.0})
            for (double sb : {0.0, 0.45, 0.55, 0.8, 1.0})
                for (double len : {0.01, 1.0, 4.0, 64.0}) {
                    const double sm = 0.5 * (sf + sb);
                    const PreintSample front = PreintegrationTable::integrateSegment(tf, sf, sm, len / 2);
                    const PreintSample back = PreintegrationTable::integrateSegment(tf, sm, sb, len / 2);
                    RayAccumulator acc;
                    acc.addPremultiplied(front.r, front.g, front.b, front.a);
                    acc.addPremultiplied(back.r, back.g, back.b, back.a);
                    const auto whole = channels(PreintegrationTable::integrateSegment(tf, sf, sb, len));
                    const std::array<double, 4> halves{acc.r, acc.g, acc.b, acc.opacity()};
                    for (int c = 0; c < 4; ++c)
                        EXPECT_NEAR(halves[c], whole[c], 1e-6) << c << " " << sf << " -> " << sb << " len " << len;
                }
}

TEST(PreintSegment, OpacityIsSymmetricInDirection) {
    const TransferFunction tf = peakedTf();
    for (double sf : {0.0, 0.3, 0.5, 0.75})
        for (double sb : {0.1, 0.52, 0.7, 1.0}) {
            const PreintSample fwd = PreintegrationTable::integrateSegment(tf, sf, sb, 3.0);
            const PreintSample rev = PreintegrationTable::integrateSegment(tf, sb, sf, 3.0);
            EXPECT_NEAR(fwd.a, rev.a, 1e-7);
        }
}

TEST(PreintTable, RejectsBadConstruction) {
    const TransferFunction tf = smoothTf();
    EXPECT_THROW(PreintegrationTable(tf, {}), Error);
    EXPECT_THROW(PreintegrationTable(tf, {1.0, 0.0}), Error);
    EXPECT_THROW(PreintegrationTable(tf, {-2.0}), Error);
    EXPECT_THROW(PreintegrationTable(tf, {std::numeric_limits<double>::infinity()}), Error);
    EXPECT_THROW(PreintegrationTable(tf, {1.0}, 1), Error);
    EXPECT_THROW(PreintegrationTable(tf, {1.0}, 0), Error);
    EXPECT_THROW(PreintegrationTable(tf, {1.0}, 5000), Error);
    EXPECT_THROW(PreintegrationTable(TransferFunction(), {1.0}), Error);
    EXPECT_THROW(PreintegrationTable::integrateSegment(TransferFunction(), 0.1, 0.2, 1.0), Error);
    const PreintegrationTable table(tf, {1.0, 2.0}, 2);
    EXPECT_THROW(table.lookup(2, 0.5f, 0.5f), Error);
    EXPECT_THROW(table.lookup(-1, 0.5f, 0.5f), Error);
    EXPECT_THROW(table.length(2), Error);
}

TEST(PreintTable, ReportsItsShape) {
    const PreintegrationTable table(smoothTf(), {0.5, 1.0, 2.0}, 16, PreintPrecision::Bits8);
    EXPECT_EQ(table.lengthCount(), 3);
    EXPECT_EQ(table.resolution(), 16);
    EXPECT_DOUBLE_EQ(table.length(2), 2.0);
    EXPECT_EQ(table.precision(), PreintPrecision::Bits8);
}

// With 257 entries the grid points i / 256 are exact floats, so lookup returns the entry bit for bit.
TEST(PreintTable, LookupAtGridPointsEqualsIntegrateSegment) {
    const TransferFunction tf = peakedTf();
    const std::vector<double> lengths{0.5, 4.0};
    for (int res : {257, 256}) {
        const PreintegrationTable table(tf, lengths, res);
        const double tol = res == 257 ? 0.0 : 1e-6;
        for (int li = 0; li < 2; ++li)
            for (int i = 0; i < res; i += 5)
                for (int j = 0; j < res; j += 7) {
                    const double sf = double(i) / (res - 1), sb = double(j) / (res - 1);
                    const auto got = channels(table.lookup(li, float(sf), float(sb)));
                    const auto want = channels(PreintegrationTable::integrateSegment(tf, sf, sb, lengths[li]));
                    for (int c = 0; c < 4; ++c) ASSERT_NEAR(got[c], want[c], tol) << res << " " << i << " " << j;
                }
    }
}

TEST(PreintTable, Bits8EntriesAreRoundedTo255ths) {
    const TransferFunction tf = peakedTf();
    const PreintegrationTable table(tf, {2.0}, 65, PreintPrecision::Bits8);
    for (int i = 0; i < 65; ++i)
        for (int j = 0; j < 65; ++j) {
            const double sf = i / 64.0, sb = j / 64.0;
            const auto got = channels(table.lookup(0, float(sf), float(sb)));
            const auto want = channels(PreintegrationTable::integrateSegment(tf, sf, sb, 2.0));
            for (int c = 0; c < 4; ++c) {
                ASSERT_NEAR(got[c], want[c], 0.5 / 255 + 1e-6);
                ASSERT_NEAR(got[c] * 255, std::round(got[c] * 255), 1e-4);  // on the 8-bit grid
            }
        }
}

TEST(PreintTable, LookupClampsOutOfRangeAndNan) {
    const PreintegrationTable table(peakedTf(), {1.0}, 33);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(channels(table.lookup(0, -5.0f, 9.0f)), channels(table.lookup(0, 0.0f, 1.0f)));
    EXPECT_EQ(channels(table.lookup(0, nan, 0.5f)), channels(table.lookup(0, 0.0f, 0.5f)));
    EXPECT_EQ(channels(table.lookup(0, 0.25f, nan)), channels(table.lookup(0, 0.25f, 0.0f)));
    EXPECT_TRUE(finiteSample(table.lookup(0, std::numeric_limits<float>::infinity(), nan)));
}

// Accuracy of the table between grid points, against the exact integral, for
// the smooth ramp at resolution 256. Float32 error is bilinear interpolation
// only; Bits8 adds up to half of 1/255 rounding on top.
TEST(PreintTable, Float32IsMoreAccurateThanBits8BetweenGridPoints) {
    const TransferFunction tf = smoothTf();
    const std::vector<double> lengths{1.0, 4.0};
    const PreintegrationTable f32(tf, lengths, 256, PreintPrecision::Float32);
    const PreintegrationTable b8(tf, lengths, 256, PreintPrecision::Bits8);
    std::mt19937 gen(20070601);
    double errF32 = 0, errB8 = 0;
    for (int n = 0; n < 4000; ++n) {
        const float sf = float(uniform01(gen)), sb = float(uniform01(gen));
        const int li = n % 2;
        const auto want = channels(PreintegrationTable::integrateSegment(tf, sf, sb, lengths[li]));
        const auto gotF = channels(f32.lookup(li, sf, sb)), gotB = channels(b8.lookup(li, sf, sb));
        for (int c = 0; c < 4; ++c) {
            errF32 = std::max(errF32, std::abs(gotF[c] - want[c]));
            errB8 = std::max(errB8, std::abs(gotB[c] - want[c]));
        }
    }
    RecordProperty("max_error_float32", std::to_string(errF32));
    RecordProperty("max_error_bits8", std::to_string(errB8));
    std::printf("[ preint   ] table vs exact, 4000 random pairs: float32 %.3g, bits8 %.3g\n", errF32, errB8);
    EXPECT_LT(errF32, errB8);
    EXPECT_LT(errF32, 5e-5);
    EXPECT_LT(errB8, 1.0 / 255);
}

TEST(PreintTable, BuildIsDeterministicAndFinite) {
    const TransferFunction tf = peakedTf();
    const std::vector<double> lengths{0.5, 1.0, 2.0, 4.0};
    const auto start = std::chrono::steady_clock::now();
    const PreintegrationTable a(tf, lengths, 256);
    a.buildAll();
    EXPECT_EQ(a.entriesBuilt(), 4 * 256 * 256);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("[ preint   ] build 256x256 x 4 lengths: %.3f s\n", seconds);
    RecordProperty("build_seconds", std::to_string(seconds));
    const PreintegrationTable b(tf, lengths, 256);
    for (int li = 0; li < 4; ++li)
        for (int i = 0; i < 256; i += 3)
            for (int j = 0; j < 256; j += 3) {
                const float sf = i / 255.0f, sb = j / 255.0f;
                ASSERT_EQ(channels(a.lookup(li, sf, sb)), channels(b.lookup(li, sf, sb)));
                ASSERT_TRUE(finiteSample(a.lookup(li, sf, sb)));
            }
}

// A lookup integrates only the blocks holding its four entries.
TEST(PreintTable, LookupsBuildOnlyTheBlocksTheyRead) {
    const PreintegrationTable t(smoothTf(), {1.0, 2.0}, 256);
    EXPECT_EQ(t.entriesBuilt(), 0);
    const float inside = 76.5f / 255;  // entries 76 and 77: one block per axis
    t.lookup(0, inside, inside);
    EXPECT_EQ(t.entriesBuilt(), kPreintBlock * kPreintBlock);
    t.lookup(0, inside, inside);  // built already
    EXPECT_EQ(t.entriesBuilt(), kPreintBlock * kPreintBlock);
    const float edge = 127.5f / 255;  // entries 127 and 128: two blocks per axis
    t.lookup(1, edge, edge);
    EXPECT_EQ(t.entriesBuilt(), 5 * kPreintBlock * kPreintBlock);
    const PreintegrationTable odd(smoothTf(), {1.0}, 21);  // the last blocks are partial: 16 + 5 per axis
    odd.buildAll();
    EXPECT_EQ(odd.entriesBuilt(), 21 * 21);
}

// Built as needed from many threads at once, or whole: the same entries,
// bit for bit, equal to the exact integrals at the grid points; the table
// keeps its own copy of a transfer function its caller let go.
TEST(PreintTable, EntriesBuiltAsNeededInParallelEqualTheWholeTable) {
    const std::vector<double> lengths{0.5, 3.0};
    const PreintegrationTable lazy(peakedTf(), lengths, 64);  // a temporary transfer function
    const PreintegrationTable whole(peakedTf(), lengths, 64);
    whole.buildAll();
    std::vector<std::array<float, 3>> pairs(20000);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (auto& p : pairs) p = {float(rng() % 2), u(rng), u(rng)};
    std::vector<PreintSample> got(pairs.size());
    tbb::parallel_for(std::size_t(0), pairs.size(), [&](std::size_t k) {
        got[k] = lazy.lookup(int(pairs[k][0]), pairs[k][1], pairs[k][2]);
    });
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const PreintSample w = whole.lookupComplete(int(pairs[k][0]), pairs[k][1], pairs[k][2]);
        ASSERT_EQ(channels(got[k]), channels(w)) << k;
    }
    const TransferFunction tf = peakedTf();
    for (int i = 0; i < 64; i += 9)
        for (int j = 0; j < 64; j += 7) {
            const PreintSample exact = PreintegrationTable::integrateSegment(tf, i / 63.0, j / 63.0, 3.0);
            const PreintSample entry = lazy.lookup(1, float(i / 63.0), float(j / 63.0));
            EXPECT_NEAR(entry.a, exact.a, 1e-6) << i << " " << j;
            EXPECT_NEAR(entry.r, exact.r, 1e-6) << i << " " << j;
        }
}

// clear() may only claim segments whose lookup is exactly zero (every
// table entry it would read integrates to zero), on either precision and
// any length, and should claim nearly every segment below the first
// extinction: checked over a fine grid of pairs and random ones.
TEST(PreintTable, ClearSegmentsLookUpExactlyZero) {
    const TransferFunction tf(0, 1, {{0.0, {0.9, 0.2, 0.1}, 0.0}, {0.3, {0.9, 0.2, 0.1}, 0.0}, {0.6, {1.0, 0.9, 0.8}, 2.0}});
    EXPECT_EQ(tf.zeroExtinctionBelow(), 0.3);
    for (PreintPrecision precision : {PreintPrecision::Float32, PreintPrecision::Bits8}) {
        const PreintegrationTable table(tf, {0.5, 8.0}, 64, precision);
        std::vector<std::array<float, 2>> pairs;
        for (int i = 0; i <= 400; ++i)
            for (int j = 0; j <= 400; j += 7) pairs.push_back({i / 400.0f, j / 400.0f});
        std::mt19937 rng(11);
        std::uniform_real_distribution<float> u(-0.1f, 0.35f);
        for (int k = 0; k < 20000; ++k) pairs.push_back({u(rng), u(rng)});
        int claimed = 0, zeroBelowFirstExtinction = 0;
        for (const auto& [front, back] : pairs) {
            const bool clear = table.clear(front, back);
            claimed += clear;
            for (int length = 0; length < 2; ++length) {
                const PreintSample s = table.lookup(length, front, back);
                if (clear) {
                    ASSERT_EQ(channels(s), channels(PreintSample{0, 0, 0, 0})) << front << " " << back;
                    // lookup() reads nothing there: the entries it would have read integrate to zero.
                    const auto cell = [](float v) { return std::min(int(std::clamp(v * 63.0f, 0.0f, 63.0f)), 62); };
                    for (int a : {cell(front), cell(front) + 1})
                        for (int b : {cell(back), cell(back) + 1}) {
                            const PreintSample e = PreintegrationTable::integrateSegment(tf, a / 63.0, b / 63.0, table.length(length));
                            ASSERT_EQ(channels(e), channels(PreintSample{0, 0, 0, 0})) << a << " " << b;
                        }
                }
            }
            // Both cells (entries at s = e / 63) wholly below s = 0.3: zero, and clear() should know it.
            if (std::max(front, back) < 17.9f / 63.0f) {
                ++zeroBelowFirstExtinction;
                EXPECT_TRUE(clear) << front << " " << back;
            }
        }
        EXPECT_GT(zeroBelowFirstExtinction, 1000);
        EXPECT_GT(claimed, zeroBelowFirstExtinction);  // and the pairs up to the last clear cell
        // Past the first extinction a segment absorbs: never clear.
        EXPECT_FALSE(table.clear(0.0f, 0.31f));
        EXPECT_GT(table.lookup(1, 0.0f, 0.35f).a, 0.0f);
    }
}

TEST(PreintTable, ClearNeverWhereZeroAbsorbsAndAlwaysWhereNothingDoes) {
    const PreintegrationTable opaque(constantTf(0.5), {1.0}, 32);
    EXPECT_EQ(constantTf(0.5).zeroExtinctionBelow(), 0.0);
    for (float s : {-1.0f, 0.0f, 1e-6f, 0.5f, 1.0f}) EXPECT_FALSE(opaque.clear(s, s)) << s;
    const PreintegrationTable empty(constantTf(0.0), {1.0, 1e6}, 32);
    EXPECT_TRUE(std::isinf(constantTf(0.0).zeroExtinctionBelow()));
    for (float s : {-1.0f, 0.0f, 0.5f, 1.0f, 2.0f}) {
        EXPECT_TRUE(empty.clear(s, 0.25f)) << s;
        EXPECT_EQ(channels(empty.lookup(1, s, 0.25f)), channels(PreintSample{0, 0, 0, 0})) << s;
    }
    // NaN reads as s = 0 in lookup; clear() may say either, but only what holds.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(opaque.clear(nan, nan));
}
