// The emission weights of pre-integration (preintegration.hpp): against
// brute-force quadrature, the constant segment's closed form, and the
// extremes (length -> 0, equal ends, huge extinction) the colour is held to.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/error.hpp"
#include "core/volume/optics/preintegration.hpp"
#include "tests/support/transfer_functions.hpp"

using namespace weft;

namespace {

using test::peakedTf;

TransferFunction constantTf(double extinction) { return TransferFunction(0, 1, {{0.0, {1, 1, 1}, extinction}, {1.0, {1, 1, 1}, extinction}}); }

// Midpoint rule in n steps over the segment, the scalar linear in x.
EmissionWeights bruteForce(const TransferFunction& tf, double sFront, double sBack, double length, int n) {
    double depth = 0, front = 0, back = 0;
    const double h = length / n;
    for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5) * h, s = sFront + (sBack - sFront) * x / length;
        const double tau = tf.atS(s).extinction;
        const double t = std::exp(-(depth + 0.5 * tau * h));  // transmittance to the midpoint
        front += (1 - x / length) * t * h, back += x / length * t * h;
        depth += tau * h;
    }
    return {float(front), float(back)};
}

// Closed form for constant extinction tau over L.
EmissionWeights constantWeights(double tau, double length) {
    const double d = tau * length;
    return {float(length * (d + std::expm1(-d)) / (d * d)), float(length * (-std::expm1(-d) - d * std::exp(-d)) / (d * d))};
}

}  // namespace

TEST(PreintEmission, MatchesBruteForceQuadrature) {
    const TransferFunction tf = peakedTf();
    const double cases[][3] = {{0.2, 0.8, 1.0}, {0.8, 0.2, 1.0}, {0.4, 0.6, 0.5}, {0.0, 1.0, 3.0}, {0.65, 0.75, 2.0}, {0.1, 0.3, 8.0}};
    for (const auto& c : cases) {
        const EmissionWeights got = PreintegrationTable::integrateEmission(tf, c[0], c[1], c[2]);
        const EmissionWeights ref = bruteForce(tf, c[0], c[1], c[2], 400000);
        EXPECT_NEAR(got.front, ref.front, 1e-5 * c[2] + 1e-7) << c[0] << " -> " << c[1] << " over " << c[2];
        EXPECT_NEAR(got.back, ref.back, 1e-5 * c[2] + 1e-7) << c[0] << " -> " << c[1] << " over " << c[2];
    }
}

// e constant along a segment of constant tau: e (1 - exp(-tau L)) / tau, the slab.
TEST(PreintEmission, ConstantSegmentIsTheSlabClosedForm) {
    for (const double tau : {1e-6, 1e-3, 0.02, 0.5, 3.0, 60.0}) {
        const TransferFunction tf = constantTf(tau);
        for (const double length : {0.25, 1.0, 4.0}) {
            const EmissionWeights w = PreintegrationTable::integrateEmission(tf, 0.5, 0.5, length);
            const double slab = -std::expm1(-tau * length) / tau;
            EXPECT_NEAR(w.front + w.back, slab, 1e-6 * slab) << tau << " " << length;
            if (tau * length > 0.1) {
                const EmissionWeights ref = constantWeights(tau, length);
                EXPECT_NEAR(w.front, ref.front, 1e-6 * ref.front) << tau << " " << length;
                EXPECT_NEAR(w.back, ref.back, 1e-6 * ref.back) << tau << " " << length;
            }
            // Unequal ends of the same extinction take the general path: the same weights.
            const EmissionWeights walked = PreintegrationTable::integrateEmission(tf, 0.3, 0.7, length);
            EXPECT_NEAR(walked.front, w.front, 1e-6 * slab) << tau << " " << length;
            EXPECT_NEAR(walked.back, w.back, 1e-6 * slab) << tau << " " << length;
        }
    }
}

// Front emission is absorbed less than back emission: it is seen first.
TEST(PreintEmission, TheFrontEndWeighsMoreUnderAbsorption) {
    const EmissionWeights w = PreintegrationTable::integrateEmission(constantTf(1.0), 0.5, 0.5, 2.0);
    EXPECT_GT(w.front, w.back);
    const EmissionWeights clear = PreintegrationTable::integrateEmission(constantTf(0.0), 0.5, 0.5, 2.0);
    EXPECT_FLOAT_EQ(clear.front, 1.0f);  // no absorption: half the length each
    EXPECT_FLOAT_EQ(clear.back, 1.0f);
}

TEST(PreintEmission, ExtremesStayFiniteNonNegativeAndBounded) {
    const TransferFunction huge = constantTf(1e300), tf = peakedTf();
    for (const double length : {0.0, 1e-300, 1e-12, 1e-3, 1.0, 1e6, 1e300}) {
        for (const TransferFunction* t : {&huge, &tf}) {
            for (const auto& s : {std::pair{0.5, 0.5}, std::pair{0.0, 1.0}, std::pair{1.0, 0.0}, std::pair{0.5, 0.5000001}}) {
                const EmissionWeights w = PreintegrationTable::integrateEmission(*t, s.first, s.second, length);
                ASSERT_TRUE(std::isfinite(w.front) && std::isfinite(w.back)) << length;
                EXPECT_GE(w.front, 0.0f);
                EXPECT_GE(w.back, 0.0f);
                EXPECT_LE(double(w.front) + w.back, length * (1 + 1e-6)) << length;  // never more than unabsorbed
            }
        }
    }
    // Length -> 0: nothing absorbs, half the length each.
    const EmissionWeights tiny = PreintegrationTable::integrateEmission(tf, 0.2, 0.8, 1e-9);
    EXPECT_NEAR(tiny.front, 0.5e-9, 1e-15);
    EXPECT_NEAR(tiny.back, 0.5e-9, 1e-15);
    // Huge extinction: only the first 1/tau of the segment shows, all of it the front's.
    const EmissionWeights opaque = PreintegrationTable::integrateEmission(constantTf(1e6), 0.5, 0.5, 1.0);
    EXPECT_NEAR(opaque.front, 1e-6, 1e-9);
    EXPECT_LT(opaque.back, 1e-11);
    EXPECT_THROW(PreintegrationTable::integrateEmission(tf, 0.2, 0.8, -1.0), Error);
    EXPECT_THROW(PreintegrationTable::integrateEmission(tf, 0.2, 0.8, std::nan("")), Error);
}

TEST(PreintEmissionTable, BuiltOnlyWhenAskedAndEqualToTheIntegralAtGridPoints) {
    const TransferFunction tf = peakedTf();
    const PreintegrationTable plain(tf, {1.0}, 17);
    EXPECT_FALSE(plain.hasEmission());
    EXPECT_THROW(plain.lookupEmission(0, 0.5f, 0.5f), Error);
    const PreintegrationTable glowing(tf, {0.5, 2.0}, 17, PreintPrecision::Float32, true);
    ASSERT_TRUE(glowing.hasEmission());
    for (int li = 0; li < 2; ++li)
        for (int i = 0; i < 17; i += 4)
            for (int j = 0; j < 17; j += 3) {
                const float sf = float(i) / 16, sb = float(j) / 16;
                const EmissionWeights got = glowing.lookupEmission(li, sf, sb);
                const EmissionWeights ref = PreintegrationTable::integrateEmission(tf, sf, sb, glowing.length(li));
                EXPECT_NEAR(got.front, ref.front, 1e-6 * glowing.length(li));
                EXPECT_NEAR(got.back, ref.back, 1e-6 * glowing.length(li));
            }
    // The colour half of the table does not change for emission.
    for (float s : {0.0f, 0.3f, 0.62f, 1.0f}) {
        const PreintSample a = plain.lookup(0, s, 1 - s), b = PreintegrationTable(tf, {1.0}, 17, PreintPrecision::Float32, true).lookup(0, s, 1 - s);
        EXPECT_EQ(a.r, b.r);
        EXPECT_EQ(a.g, b.g);
        EXPECT_EQ(a.b, b.b);
        EXPECT_EQ(a.a, b.a);
    }
}

TEST(PreintEmissionTable, Bits8WeightsAreRoundedTo255thsOfTheLength) {
    const PreintegrationTable t(peakedTf(), {2.0}, 9, PreintPrecision::Bits8, true);
    for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 9; ++j) {
            const EmissionWeights w = t.lookupEmission(0, float(i) / 8, float(j) / 8);
            for (const float v : {w.front, w.back}) {
                const float steps = v / 2.0f * 255.0f;
                EXPECT_NEAR(steps, std::round(steps), 1e-3f);
            }
        }
}
