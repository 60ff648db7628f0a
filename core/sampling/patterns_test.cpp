// Pattern generators and sets: published discrepancies, net structure,
// Poisson-disk distance, unbiasedness, interleaving and determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "core/base/error.hpp"
#include "core/sampling/generators.hpp"
#include "core/sampling/pattern_analysis.hpp"
#include "core/sampling/pattern_set.hpp"

using namespace weft;

namespace {

std::vector<Vec2> points(const std::string& name, int n, std::uint64_t seed = 1,
                         std::map<std::string, std::string> options = {}) {
    return generatePoints(name, n, options, seed);
}

// Every elementary interval [a/2^i, (a+1)/2^i) x [b/2^j, (b+1)/2^j) with
// i + j = m holds exactly one of the 2^m points.
bool isZeroM2Net(const std::vector<Vec2>& p, int m) {
    for (int i = 0; i <= m; ++i) {
        const int j = m - i;
        std::vector<int> hits(std::size_t(1) << m, 0);
        for (const Vec2& q : p) {
            const int a = int(q.x * (1 << i)), b = int(q.y * (1 << j));
            if (++hits[std::size_t(a) * (std::size_t(1) << j) + b] > 1) return false;
        }
    }
    return true;
}

}  // namespace

TEST(Discrepancy, CentredFourByFourGridMatchesPublishedValue) {
    EXPECT_NEAR(l2StarDiscrepancy(points("regular", 16)), 0.0597258, 5e-7);
}

TEST(Discrepancy, HammersleyMatchesPublishedValues) {
    EXPECT_NEAR(l2StarDiscrepancy(points("hammersley", 16)), 0.0692908, 5e-7);
    EXPECT_NEAR(l2StarDiscrepancy(points("hammersley", 256)), 0.00627723, 5e-9);
}

TEST(Discrepancy, OneDimensionalMidpointsAreOneOverRootTwelveN) {
    for (int n : {1, 2, 7, 64, 333}) {
        std::vector<double> xs;
        for (int i = 0; i < n; ++i) xs.push_back((i + 0.5) / n);
        const double expected = 1.0 / (std::sqrt(12.0) * n);
        EXPECT_NEAR(l2StarDiscrepancy1D(xs), expected, 1e-6 * expected) << n;
    }
}

TEST(Discrepancy, LowDiscrepancySetsBeatRandomPoints) {
    const double random = l2StarDiscrepancy(points("random", 1024));
    EXPECT_LT(l2StarDiscrepancy(points("lp", 1024)), 0.25 * random);
    EXPECT_LT(l2StarDiscrepancy(points("jittered", 1024)), 0.5 * random);
}

TEST(Nets, HammersleyAndLpFillEveryElementaryIntervalOnce) {
    for (int m = 0; m <= 10; ++m)
        for (const char* name : {"hammersley", "lp"})
            for (const char* scramble : {"none", "xor", "owen"})
                for (std::uint64_t seed : {1u, 7u})
                    EXPECT_TRUE(isZeroM2Net(points(name, 1 << m, seed, {{"scramble", scramble}}), m))
                        << name << " scramble=" << scramble << " m=" << m << " seed=" << seed;
}

TEST(Nets, RandomPointsAreNotNets) {
    EXPECT_FALSE(isZeroM2Net(points("random", 256), 8));
    EXPECT_FALSE(isZeroM2Net(points("jittered", 256), 8));  // stratified, but not in every shape
}

TEST(Nets, ScramblingMovesPointsAndIsSeeded) {
    const auto plain = points("lp", 64, 3, {{"scramble", "none"}});
    const auto a = points("lp", 64, 3, {{"scramble", "owen"}}), b = points("lp", 64, 4, {{"scramble", "owen"}});
    EXPECT_NE(plain[5].y, a[5].y);
    EXPECT_NE(a[5].y, b[5].y);
}

TEST(Poisson, MinimumDistanceHoldsAndBothTestsAgree) {
    for (int n : {2, 16, 100, 2048}) {
        const PoissonResult grid = poissonDartThrowing(n, 0.7, 11, true);
        const PoissonResult plain = poissonDartThrowing(n, 0.7, 11, false);
        ASSERT_EQ(int(grid.points.size()), n);
        EXPECT_GE(neighbourDistances(grid.points).min, grid.radius) << n;
        EXPECT_GT(grid.radius, 0.5 * hexagonalDistance(n)) << n;
        ASSERT_EQ(grid.points.size(), plain.points.size());
        for (std::size_t i = 0; i < grid.points.size(); ++i) EXPECT_EQ(grid.points[i].x, plain.points[i].x);
    }
}

TEST(Poisson, NearJammingStillDeliversEveryPoint) {
    const PoissonResult r = poissonDartThrowing(500, 0.76, 5, true);
    EXPECT_EQ(r.points.size(), 500u);
    EXPECT_GE(neighbourDistances(r.points).min, r.radius);
}

TEST(BlueNoise, RelaxedAndDiffusedPointsKeepTheirDistance) {
    // Uniform random points come much closer (expected minimum ~ 1/N).
    const double hex = hexagonalDistance(256);
    EXPECT_LT(neighbourDistances(points("random", 256)).min, 0.2 * hex);
    EXPECT_GT(neighbourDistances(points("lloyd", 256)).min, 0.5 * hex);
    EXPECT_GT(neighbourDistances(points("point_diffusion", 256)).min, 0.35 * hex);
    EXPECT_LT(neighbourDistances(points("lloyd", 256)).max, 1.5 * hex);
}

TEST(Generators, ExactCountInsideTheUnitSquareAndDeterministic) {
    for (const PatternGeneratorInfo* g : patternGenerators().all())
        for (int n : {1, 3, 16, 50}) {
            const auto a = g->generate(n, g->options.parse({}), 9), b = g->generate(n, g->options.parse({}), 9);
            ASSERT_EQ(int(a.size()), n) << g->name;
            for (std::size_t i = 0; i < a.size(); ++i) {
                EXPECT_TRUE(a[i].x >= 0 && a[i].x < 1 && a[i].y >= 0 && a[i].y < 1) << g->name;
                EXPECT_EQ(a[i].x, b[i].x) << g->name;
                EXPECT_EQ(a[i].y, b[i].y) << g->name;
            }
        }
}

TEST(Generators, SeedsGiveDifferentSetsExceptForDeterministicOnes) {
    for (const char* name : {"jittered", "random", "poisson", "point_diffusion", "lloyd", "lp"}) {
        const auto a = points(name, 32, 1), b = points(name, 32, 2);
        bool differ = false;
        for (std::size_t i = 0; i < a.size(); ++i) differ |= a[i].x != b[i].x || a[i].y != b[i].y;
        EXPECT_TRUE(differ) << name;
    }
}

TEST(Generators, UnknownNamesAndBadOptionsAreClearErrors) {
    EXPECT_THROW(points("blue", 4), Error);
    EXPECT_THROW(points("poisson", 4, 1, {{"radius", "2"}}), Error);
    EXPECT_THROW(points("lp", 4, 1, {{"scramble", "maybe"}}), Error);
    EXPECT_THROW(makePatternSet("interleaved:0x4", 4, 1), Error);
    EXPECT_THROW(makePatternSet("interleaved:4x4,basis=interleaved", 4, 1), Error);
    EXPECT_THROW(makePatternSet("jittered:4x4", 4, 1), Error);
    EXPECT_THROW(makePatternSet("jittered,=3", 4, 1), Error);
}

// Mean of f over a pattern of n points; t statistic of that estimator over
// fixed seeds against the exact integral.
template <class F>
double tStatistic(const std::string& spec, int n, F f, double exact) {
    const int seeds = 400;
    double sum = 0, sumSq = 0;
    for (int s = 0; s < seeds; ++s) {
        const PatternSet set = makePatternSet(spec, n, 1000 + s);
        double est = 0;
        for (const Vec2& p : set.tilePoints()) est += f(p.x / set.tileWidth(), p.y / set.tileHeight());
        est /= double(n) * set.patternCount();
        sum += est, sumSq += est * est;
    }
    const double mean = sum / seeds, var = (sumSq - seeds * mean * mean) / (seeds - 1);
    return (mean - exact) / std::sqrt(var / seeds);
}

TEST(Unbiased, StratifiedAndInterleavedMeansOfKnownIntegrals) {
    auto disc = [](double x, double y) { return (x - 0.5) * (x - 0.5) + (y - 0.45) * (y - 0.45) < 0.16 ? 1.0 : 0.0; };
    auto product = [](double x, double y) { return x * y * y; };
    auto wave = [](double x, double y) { return std::sin(7 * x + 3 * y) + 1; };
    const double waveExact = 1 + (std::sin(3.0) + std::sin(7.0) - std::sin(10.0)) / 21.0;
    for (const char* spec : {"jittered", "random", "lp", "interleaved:2x2,basis=jittered", "interleaved:4x2,basis=lp"}) {
        EXPECT_LT(std::abs(tStatistic(spec, 16, disc, std::numbers::pi * 0.16)), 4.0) << spec;
        EXPECT_LT(std::abs(tStatistic(spec, 16, product, 1.0 / 6.0)), 4.0) << spec;
        EXPECT_LT(std::abs(tStatistic(spec, 16, wave, waveExact)), 4.0) << spec;
    }
}

TEST(Unbiased, TheTestHasThePowerToSeeASmallBias) {
    // The same estimator against a value 5% off: the t test must reject it.
    auto product = [](double x, double y) { return x * y * y; };
    EXPECT_GT(std::abs(tStatistic("jittered", 16, product, 1.05 / 6.0)), 4.0);
}

TEST(PatternSet, InterleavedSetGivesEveryPixelItsOwnPatternOfSppPoints) {
    const PatternSet set = makePatternSet("interleaved:4x4,basis=lp", 4, 3);
    EXPECT_EQ(set.patternCount(), 16);
    EXPECT_EQ(set.patternIndex(5, 2), set.patternIndex(1, 6));
    EXPECT_EQ(set.patternIndex(-1, -1), set.patternIndex(3, 3));
    // 64 points of a (0,6,2)-net over the 4x4 tile: every pixel gets 4, so the
    // tile's points normalised to the unit square are the net again.
    std::vector<Vec2> unit;
    for (const Vec2& p : set.tilePoints()) unit.push_back({p.x / 4, p.y / 4});
    EXPECT_TRUE(isZeroM2Net(unit, 6));
    std::set<std::pair<float, float>> firsts;
    for (int j = 0; j < 16; ++j) firsts.insert({set.pattern(j)[0].x, set.pattern(j)[0].y});
    EXPECT_EQ(firsts.size(), 16u);  // neighbouring pixels differ
}

TEST(PatternSet, BalancingKeepsExactlySppPerPixelForAnyBasis) {
    for (const char* basis : {"random", "poisson", "lloyd", "point_diffusion", "hammersley"}) {
        const PatternSet set = makePatternSet(std::string("interleaved:3x2,basis=") + basis, 5, 1);
        EXPECT_EQ(set.tilePoints().size(), 30u) << basis;
        for (const Vec2& p : set.tilePoints()) EXPECT_TRUE(p.x >= 0 && p.x < 3 && p.y >= 0 && p.y < 2) << basis;
    }
}

TEST(PatternSet, ThirdCoordinateIsStratifiedInEachPixelAndOverTheTile) {
    const PatternSet set = makePatternSet("interleaved:4x4", 4, 8);
    std::vector<int> strata(64, 0);
    for (int j = 0; j < 16; ++j) {
        std::vector<int> own(4, 0);
        for (int k = 0; k < 4; ++k) ++strata[int(set.pattern(j)[k].t * 64)], ++own[int(set.pattern(j)[k].t * 4)];
        for (int s : own) EXPECT_EQ(s, 1) << "pixel " << j;
    }
    for (int s : strata) EXPECT_EQ(s, 1);
}

TEST(PatternSet, SameSpecAndSeedSameSet) {
    const PatternSet a = makePatternSet("interleaved:4x4,basis=poisson,radius=0.7", 4, 5);
    const PatternSet b = makePatternSet("interleaved:4x4,basis=poisson,radius=0.7", 4, 5);
    for (int j = 0; j < 16; ++j)
        for (int k = 0; k < 4; ++k) {
            EXPECT_EQ(a.pattern(j)[k].x, b.pattern(j)[k].x);
            EXPECT_EQ(a.pattern(j)[k].t, b.pattern(j)[k].t);
        }
}

TEST(Periodogram, RegularGridHasPeaksOnlyOnItsReciprocalLattice) {
    const auto spec = periodogram(points("regular", 16), 8);
    for (int fy = -8; fy <= 8; ++fy)
        for (int fx = -8; fx <= 8; ++fx) {
            const double v = spec[std::size_t(fy + 8) * 17 + fx + 8];
            if (fx % 4 == 0 && fy % 4 == 0) EXPECT_NEAR(v, 16.0, 1e-9);
            else EXPECT_NEAR(v, 0.0, 1e-9);
        }
}

TEST(Periodogram, WhiteNoiseIsFlatAndBlueNoiseLacksLowFrequencies) {
    auto averaged = [](const char* name, std::map<std::string, std::string> options) {
        std::vector<double> sum;
        for (int s = 0; s < 24; ++s) {
            const auto p = periodogram(points(name, 256, s, options), 24);
            if (sum.empty()) sum.assign(p.size(), 0);
            for (std::size_t i = 0; i < p.size(); ++i) sum[i] += p[i] / 24;
        }
        return radialAverage(sum, 24);
    };
    const auto white = averaged("random", {}), blue = averaged("lloyd", {{"iterations", "10"}, {"oversample", "16"}});
    double whiteMean = 0, blueLow = 0;
    for (const RadialBin& b : white) whiteMean += b.power / white.size();
    for (int r = 1; r <= 6; ++r) blueLow += blue[r - 1].power / 6;  // sqrt(256) = 16: well below
    EXPECT_NEAR(whiteMean, 1.0, 0.05);
    EXPECT_LT(blueLow, 0.2);
    EXPECT_GT(blue[19].power, 0.8);  // and the energy is at high frequencies
}

TEST(Periodogram, RepeatedPatternHasEnergyOnlyOnTheTileLatticeInterleavedSpreadsIt) {
    // Keller & Heidrich, Figure 1: the same pattern in every pixel of a 4x4
    // tile is periodic with the pixel, so its spectrum (in cycles per tile)
    // lives on multiples of 4; an interleaved set is not.
    auto scaled = [](const PatternSet& set, int tile) {
        std::vector<Vec2> out;
        for (int y = 0; y < tile; ++y)
            for (int x = 0; x < tile; ++x)
                for (int k = 0; k < set.samplesPerPixel(); ++k) {
                    const PatternPoint& p = set.sample(x, y, k);
                    out.push_back({(x + p.x) / tile, (y + p.y) / tile});
                }
        return out;
    };
    const auto repeated = periodogram(scaled(makePatternSet("jittered", 4, 2), 4), 12);
    const auto interleaved = periodogram(scaled(makePatternSet("interleaved:4x4,basis=jittered", 4, 2), 4), 12);
    double offLatticeRepeated = 0, offLatticeInterleaved = 0;
    for (int fy = -12; fy <= 12; ++fy)
        for (int fx = -12; fx <= 12; ++fx) {
            if (fx % 4 == 0 && fy % 4 == 0) continue;
            offLatticeRepeated += repeated[std::size_t(fy + 12) * 25 + fx + 12];
            offLatticeInterleaved += interleaved[std::size_t(fy + 12) * 25 + fx + 12];
        }
    EXPECT_LT(offLatticeRepeated, 1e-9);
    EXPECT_GT(offLatticeInterleaved, 100.0);
}

TEST(Convergence, StratificationBeatsRandomOnAnEdge) {
    // RMS error of the mean of a disc indicator over seeds: random points
    // converge as N^-1/2 (x4 from 16 to 256 points), stratified and
    // Owen-scrambled net points as N^-3/4 on an edge (x8).
    auto rmsError = [](const char* name, int n, std::map<std::string, std::string> options = {}) {
        const double exact = std::numbers::pi * 0.16;
        double sq = 0;
        for (int s = 0; s < 200; ++s) {
            double est = 0;
            for (const Vec2& p : points(name, n, 500 + s, options))
                est += (p.x - 0.5) * (p.x - 0.5) + (p.y - 0.45) * (p.y - 0.45) < 0.16 ? 1.0 : 0.0;
            sq += (est / n - exact) * (est / n - exact);
        }
        return std::sqrt(sq / 200);
    };
    const double random = rmsError("random", 16) / rmsError("random", 256);
    const double jittered = rmsError("jittered", 16) / rmsError("jittered", 256);
    const double lp = rmsError("lp", 16, {{"scramble", "owen"}}) / rmsError("lp", 256, {{"scramble", "owen"}});
    EXPECT_GT(random, 3.0);
    EXPECT_LT(random, 5.5);
    EXPECT_GT(jittered, 6.0);
    EXPECT_GT(lp, 6.0);
}
