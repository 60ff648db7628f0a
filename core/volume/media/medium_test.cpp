// The scene's media against closed forms: transmittance of a homogeneous
// box (delta and ratio tracking), a non-absorbing medium returns every
// walker (the furnace), Henyey-Greenstein sampling matches its density
// (chi-square), delta and ratio tracking agree through a heterogeneous grid
// (Welch t-test), and extreme coefficients stay finite.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/volume/media/medium.hpp"
#include "tests/support/volume_fixtures.hpp"

using namespace weft;
using weft::test::cubeVolume;

namespace {

Volume homogeneousCube(int res, const Vec3d& absorb, const Vec3d& scatter) {
    return cubeVolume(res, absorb, scatter, [](int, int, int) { return 1.0f; });
}

struct Moments {
    Vec3d mean{0.0}, var{0.0};
    int n = 0;
};

template <class Draw>
Moments moments(int n, const Draw& draw) {
    Moments m;
    Vec3d sum(0.0), sum2(0.0);
    for (int i = 0; i < n; ++i) {
        const Vec3d x = draw();
        sum += x, sum2 += x * x;
    }
    m.n = n, m.mean = sum / double(n);
    for (int c = 0; c < 3; ++c) m.var[c] = std::max(0.0, sum2[c] / n - m.mean[c] * m.mean[c]);
    return m;
}

double standardError(const Moments& m, int c) { return std::sqrt(m.var[c] / m.n); }

using Estimator = Vec3d (*)(MediumRay&, Rng&, std::int64_t&);

}  // namespace

TEST(Medium, HomogeneousBoxTransmittanceIsExponential) {
    // Per voxel coefficients; the cube has 16 voxels per unit, so sigma per
    // world unit is 16 x (absorb + scatter). The ray stays inside voxels of
    // density 1 (away from the trilinear ramp at the faces).
    const Vec3d absorb(0.01, 0.02, 0.05), scatter(0.02, 0.04, 0.05);
    const Volume v = homogeneousCube(16, absorb, scatter);
    const std::vector<Volume> held{v};  // Medium keeps pointers into it
    const Medium medium(held);
    const double d = 0.6;
    for (Estimator estimate : {&ratioTrackingTransmittance, &deltaTrackingTransmittance}) {
        MediumRay ray(medium);
        Rng rng(7);
        std::int64_t collisions = 0;
        const Moments m = moments(40000, [&] {
            ray.reset(Vec3d(0.2, 0.5, 0.5), Vec3d(1, 0, 0), d);
            return estimate(ray, rng, collisions);
        });
        for (int c = 0; c < 3; ++c) {
            const double exact = std::exp(-16.0 * (absorb[c] + scatter[c]) * d);
            EXPECT_NEAR(m.mean[c], exact, 4.0 * standardError(m, c) + 1e-9) << "channel " << c;
        }
        EXPECT_GT(collisions, 0);
    }
}

TEST(Medium, SegmentsConvertIndexDistanceToWorldDistance) {
    const Volume v = homogeneousCube(16, Vec3d(0.1), Vec3d(0.1));
    const std::vector<Volume> held{v};  // Medium keeps pointers into it
    const Medium medium(held);
    MediumRay ray(medium);
    ray.reset(Vec3d(-1, 0.5, 0.5), Vec3d(1, 0, 0), 10.0);
    ASSERT_EQ(ray.segments().size(), 1u);
    // index box [-1, 16] padded: world x from -1/16 to 1 + 1/16... measured from x = -1.
    EXPECT_NEAR(ray.segments()[0].t0, 1.0 - 1.0 / 16, 1e-9);
    EXPECT_NEAR(ray.segments()[0].t1, 1.0 + 16.0 / 16, 1e-9);
    EXPECT_NEAR(ray.at(1.5).extinction[0], 16 * 0.2, 1e-9);  // world x = 0.5, inside
}

TEST(Medium, OverlappingVolumesAddTheirExtinction) {
    const Volume a = homogeneousCube(16, Vec3d(0.1), Vec3d(0.0)), b = homogeneousCube(8, Vec3d(0.0), Vec3d(0.3));
    const std::vector<Volume> held{a, b};  // Medium keeps pointers into it
    const Medium medium(held);
    MediumRay ray(medium);
    ray.reset(Vec3d(0.5, 0.5, -1), Vec3d(0, 0, 1), 10.0);
    ASSERT_EQ(ray.segments().size(), 2u);
    const MediumCoefficients c = ray.at(1.5);
    EXPECT_NEAR(c.extinction[1], 16 * 0.1 + 8 * 0.3, 1e-9);
    EXPECT_NEAR(c.scattering[1], 8 * 0.3, 1e-9);
    EXPECT_GE(ray.majorantAt(1.5).majorant, c.extinction[1]);
}

TEST(Medium, NonAbsorbingMediumReturnsEveryWalker) {
    // Albedo 1 in every channel (chromatic, heterogeneous): a random walk
    // ends only by leaving, so the expected escaped weight is 1 per channel.
    const Volume v = cubeVolume(16, Vec3d(0.0), Vec3d(0.3, 0.6, 1.2),
                                [](int i, int j, int k) { return float(0.2 + 0.8 * ((i * 7 + j * 3 + k * 5) % 11) / 10.0); });
    const std::vector<Volume> held{v};  // Medium keeps pointers into it
    const Medium medium(held);
    MediumRay ray(medium);
    Rng rng(3);
    std::int64_t collisions = 0;
    int scatterings = 0;
    const Moments m = moments(4000, [&] {
        Vec3d beta(1.0), o(0.5, 0.5, 0.5), d = sampleHenyeyGreenstein(Vec3d(0, 0, 1), 0.0, rng.uniformDouble(), rng.uniformDouble());
        for (int bounce = 0; bounce < 100000; ++bounce) {
            ray.reset(o, d, 1e30);
            const FreeFlight f = sampleFreeFlight(ray, rng, beta, collisions);
            if (!f.scattered) return beta;
            ++scatterings;
            o = o + d * f.t;
            d = sampleHenyeyGreenstein(d, 0.5, rng.uniformDouble(), rng.uniformDouble());
        }
        return Vec3d(0.0);
    });
    EXPECT_GT(scatterings, 4000 * 3);  // optically thick: walkers scatter many times
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.mean[c], 1.0, 4.0 * standardError(m, c) + 1e-12) << "channel " << c;
}

TEST(Medium, HenyeyGreensteinSamplingMatchesItsDensity) {
    const int bins = 40, n = 200000;
    for (double g : {-0.99, -0.6, 0.0, 0.3, 0.8, 0.99}) {
        std::vector<double> expected(bins), observed(bins, 0.0);
        // The exact mass of each bin: 2 pi HG integrates in closed form,
        // (1 - g^2) / (2 g) (1 + g^2 - 2 g mu)^(-1/2) (+ const).
        auto cdf = [g](double mu) {
            if (g == 0) return 0.5 * (mu + 1);
            return (1 - g * g) / (2 * g) * (1 / std::sqrt(1 + g * g - 2 * g * mu) - 1 / (1 + g));
        };
        for (int b = 0; b < bins; ++b) expected[b] = n * (cdf(-1.0 + 2.0 * (b + 1) / bins) - cdf(-1.0 + 2.0 * b / bins));
        Rng rng(19);
        double meanCos = 0;
        for (int i = 0; i < n; ++i) {
            const double mu = sampleHenyeyGreensteinCos(g, rng.uniformDouble());
            observed[std::min(bins - 1, int((mu + 1.0) * 0.5 * bins))] += 1;
            meanCos += mu / n;
        }
        // Pool sparse bins so each term of the statistic is well behaved.
        double chi2 = 0, e = 0, o = 0;
        int dof = -1;
        for (int b = 0; b < bins; ++b) {
            e += expected[b], o += observed[b];
            if (e < 20 && b + 1 < bins) continue;
            chi2 += (o - e) * (o - e) / e, ++dof, e = o = 0;
        }
        // 99.9% quantile of chi-square (Wilson-Hilferty).
        const double z = 3.09, q = dof * std::pow(1 - 2.0 / (9 * dof) + z * std::sqrt(2.0 / (9 * dof)), 3);
        EXPECT_LT(chi2, q) << "g " << g << " dof " << dof;
        EXPECT_NEAR(meanCos, g, 0.01) << "g " << g;  // the mean cosine of HG is g
    }
}

TEST(Medium, HenyeyGreensteinDirectionsFollowTheTravelDirection) {
    Rng rng(5);
    const Vec3d d = Vec3d(0.3, -0.5, 0.8).unit();
    double mean = 0;
    for (int i = 0; i < 100000; ++i) {
        const Vec3d w = sampleHenyeyGreenstein(d, 0.7, rng.uniformDouble(), rng.uniformDouble());
        ASSERT_NEAR(w.length(), 1.0, 1e-9);
        mean += w.dot(d) / 100000;
    }
    EXPECT_NEAR(mean, 0.7, 0.01);
}

TEST(Medium, DeltaAndRatioTrackingAgreeThroughAHeterogeneousGrid) {
    const Volume v = cubeVolume(24, Vec3d(0.02, 0.05, 0.1), Vec3d(0.1, 0.1, 0.05), [](int i, int j, int k) {
        return float(0.5 + 0.5 * std::sin(0.7 * i) * std::cos(0.4 * j + 0.3 * k));
    });
    const std::vector<Volume> held{v};  // Medium keeps pointers into it
    const Medium medium(held);
    Moments m[2];
    int e = 0;
    for (Estimator estimate : {&ratioTrackingTransmittance, &deltaTrackingTransmittance}) {
        MediumRay ray(medium);
        Rng rng(29 + e);
        std::int64_t collisions = 0;
        m[e++] = moments(40000, [&] {
            ray.reset(Vec3d(-0.5, 0.1, 0.2), Vec3d(1.0, 0.35, 0.5).unit(), 1e30);
            return estimate(ray, rng, collisions);
        });
    }
    for (int c = 0; c < 3; ++c) {
        const double se = std::sqrt(m[0].var[c] / m[0].n + m[1].var[c] / m[1].n);
        const double t = (m[0].mean[c] - m[1].mean[c]) / se;
        EXPECT_LT(std::abs(t), 4.0) << "channel " << c << " ratio " << m[0].mean[c] << " delta " << m[1].mean[c];
        EXPECT_GT(m[0].mean[c], 0.05);  // the ray does cross the medium
        EXPECT_LT(m[0].mean[c], 0.95);
        EXPECT_LT(m[0].var[c], m[1].var[c]);  // ratio tracking is the smoother one
    }
}

TEST(Medium, ExtremeCoefficientsStayFinite) {
    for (double k : {1e-30, 1e12}) {
        const Volume v = homogeneousCube(8, Vec3d(k), Vec3d(k));
        const std::vector<Volume> held{v};  // Medium keeps pointers into it
        const Medium medium(held);
        MediumRay ray(medium);
        Rng rng(1);
        std::int64_t collisions = 0;
        for (Estimator estimate : {&ratioTrackingTransmittance, &deltaTrackingTransmittance})
            for (int i = 0; i < 20; ++i) {
                ray.reset(Vec3d(-1, 0.5, 0.5), Vec3d(1, 0, 0), 1e30);
                const Vec3d T = estimate(ray, rng, collisions);
                for (int c = 0; c < 3; ++c) {
                    ASSERT_TRUE(std::isfinite(T[c])) << k;
                    ASSERT_GE(T[c], 0.0);
                    ASSERT_LE(T[c], 1.0) << k;
                }
                if (k > 1) EXPECT_EQ(T[0], 0.0);
                else EXPECT_EQ(T[0], 1.0);
            }
        Vec3d beta(1.0);
        ray.reset(Vec3d(0.5, 0.5, 0.5), Vec3d(1, 0, 0), 1e30);  // inside, where density is exactly 1
        const FreeFlight f = sampleFreeFlight(ray, rng, beta, collisions);
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(beta[c]) && std::isfinite(f.t)) << k;
        EXPECT_EQ(f.scattered, k > 1);
    }
}

TEST(Medium, NonFiniteVoxelsReadAsEmpty) {
    const Volume v = cubeVolume(8, Vec3d(0.1), Vec3d(0.1), [](int i, int, int) {
        return i < 4 ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
    });
    const std::vector<Volume> held{v};  // Medium keeps pointers into it
    const Medium medium(held);
    MediumRay ray(medium);
    ray.reset(Vec3d(-1, 0.5, 0.5), Vec3d(1, 0, 0), 1e30);
    Rng rng(2);
    std::int64_t collisions = 0;
    const Vec3d T = ratioTrackingTransmittance(ray, rng, collisions);
    EXPECT_EQ(T[1], 1.0);
}

TEST(Medium, BrickMajorantsBoundTheExtinctionAndSkipEmptySpace) {
    // Dense in the lower x half, empty in the upper (beyond one brick of
    // trilinear support), under a rotated, anisotropic transform.
    Volume v = cubeVolume(32, Vec3d(0.05), Vec3d(0.2, 0.3, 0.4), [](int i, int j, int k) {
        return i < 12 ? float(0.5 + 0.5 * std::sin(1.3 * i + 0.7 * j) * std::cos(0.9 * k)) : 0.0f;
    });
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.preScale(Vec3d(1.0, 2.0, 0.5));
    m.postRotate(openvdb::math::Y_AXIS, 0.6);
    v.grid = placeGrid(v.grid, m);
    const std::vector<Volume> held{v};  // Medium keeps pointers into it
    const Medium medium(held);
    MediumRay ray(medium);
    Rng rng(13);
    int emptySteps = 0;
    for (int r = 0; r < 200; ++r) {
        const Vec3d o(rng.uniformDouble() * 0.3, rng.uniformDouble() * 2 - 0.2, rng.uniformDouble() * 0.5 - 0.3);
        const Vec3d d = sampleHenyeyGreenstein(Vec3d(1, 0, 0), 0.0, rng.uniformDouble(), rng.uniformDouble());
        ray.reset(o - d * 3.0, d, 1e30);
        if (ray.empty()) continue;
        for (double t = 0; t < ray.end(); t += 0.003) {
            const MajorantSpan span = ray.majorantAt(t);
            const Vec3d s = ray.at(t).extinction;
            ASSERT_GE(span.majorant, std::max({s[0], s[1], s[2]}) * (1 - 1e-9)) << "ray " << r << " t " << t;
            ASSERT_GT(span.next, t);
            emptySteps += span.majorant == 0.0;
        }
    }
    EXPECT_GT(emptySteps, 1000);  // the empty half costs no collisions
}

TEST(Medium, OverlappingPhaseFunctionsMixByScattering) {
    // Two cubes overlap with different g and chromatic scattering: the
    // weighted lobe pick estimates, per channel, the mixture's mean cosine
    // sum_i sigma_s,i g_i / sum_i sigma_s,i.
    Volume a = homogeneousCube(16, Vec3d(0.0), Vec3d(0.3, 0.1, 0.2)), b = homogeneousCube(16, Vec3d(0.0), Vec3d(0.1, 0.3, 0.2));
    a.medium.g = 0.8, b.medium.g = -0.5;
    const std::vector<Volume> held{a, b};  // Medium keeps pointers into it
    const Medium medium(held);
    MediumRay ray(medium);
    ray.reset(Vec3d(0.5, 0.5, -1), Vec3d(0, 0, 1), 10.0);
    const MediumCoefficients c = ray.at(1.5);
    Rng rng(23);
    const Moments m = moments(100000, [&] {
        Vec3d w(1.0);
        const double g = ray.pickPhase(rng, w);
        return w * sampleHenyeyGreensteinCos(g, rng.uniformDouble());
    });
    for (int k = 0; k < 3; ++k) {
        const double sa = a.medium.scatter[k], sb = b.medium.scatter[k];
        EXPECT_NEAR(m.mean[k], (sa * 0.8 - sb * 0.5) / (sa + sb), 4 * standardError(m, k)) << "channel " << k;
    }
    EXPECT_NEAR(c.scattering[0], 16 * 0.4, 1e-9);
}
