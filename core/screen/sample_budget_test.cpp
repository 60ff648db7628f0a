// SampleBudget: the importance map against a brute-force W_p, the Hamilton
// apportionment as property tests over random maps and budgets (exact sum,
// minimum, quotas within one sample, largest remainders first, determinism,
// thread independence), its documented extremes, and the scan and batch
// buffers mapping every sample to its pixel exactly once.
#include "core/screen/sample_budget.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numeric>

#include "core/base/error.hpp"
#include "core/base/rng.hpp"

using namespace weft;

namespace {

GeometryGuides stepGuides(int w, int h, std::uint64_t seed) {
    // Three walls (normals x, y, z) with a depth step, plus some noise.
    Rng rng(seed);
    GeometryGuides g{w, h, {}, {}};
    g.normal.resize(std::size_t(w) * h), g.position.resize(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            const int wall = x < w / 3 ? 0 : x < 2 * w / 3 ? 1 : 2;
            g.normal.set(i, wall == 0, wall == 1, wall == 2);
            g.position.set(i, x * 0.01f, y * 0.01f + (y > h / 2 ? 0.5f : 0.0f), rng.uniform() * 0.002f);
        }
    return g;
}

// W_p by definition, in double.
double bruteImportance(const GeometryGuides& g, int x, int y, int k, double sn, double sp) {
    const int lo = -(k / 2), hi = (k - 1) / 2;
    double w = 0;
    int n = 0;
    const std::size_t p = std::size_t(y) * g.width + x;
    for (int dy = lo; dy <= hi; ++dy)
        for (int dx = lo; dx <= hi; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= g.width || qy >= g.height) continue;
            const std::size_t q = std::size_t(qy) * g.width + qx;
            w += std::exp(-distance2(g.normal, p, q) / (sn * sn) - distance2(g.position, p, q) / (sp * sp));
            ++n;
        }
    return 1.0 - w / n;
}

struct Case {
    std::vector<float> importance;
    std::vector<std::uint8_t> active;
    BudgetRequest request;
};

// Random maps of several shapes: uniform, sparse, few distinct values (ties), masked.
Case randomCase(std::uint64_t seed) {
    Rng rng(seed);
    Case c;
    const std::size_t n = 1 + rng.next() % 700;
    c.importance.resize(n);
    const int shape = int(rng.next() % 4);
    for (float& v : c.importance) {
        const float u = rng.uniform();
        v = shape == 0 ? u : shape == 1 ? (u < 0.9f ? 0.0f : u * 100) : shape == 2 ? float(int(u * 3)) * 0.25f : u * u;
    }
    if (rng.next() % 3 == 0) {
        c.active.resize(n);
        for (auto& a : c.active) a = rng.uniform() < 0.8f;
    }
    c.request.minimum = int(rng.next() % 4);
    c.request.budget = std::int64_t(rng.next() % (n * 20 + 1));
    c.request.tieSeed = seed;
    return c;
}

std::int64_t sum(const std::vector<std::uint32_t>& v) { return std::accumulate(v.begin(), v.end(), std::int64_t(0)); }

}  // namespace

TEST(Importance, MatchesTheDefinitionForEveryWindow) {
    const GeometryGuides g = stepGuides(23, 17, 1);
    for (int k = 2; k <= 10; ++k) {
        ImportanceSettings s;
        s.window = k, s.sigmaNormal = 0.4f, s.sigmaPosition = 0.05f;
        const std::vector<float> imp = geometryImportance(g, s);
        for (int y = 0; y < g.height; ++y)
            for (int x = 0; x < g.width; ++x) {
                const float v = imp[std::size_t(y) * g.width + x];
                ASSERT_NEAR(v, bruteImportance(g, x, y, k, 0.4, 0.05), 2e-6) << k << " " << x << "," << y;
                ASSERT_TRUE(v >= 0 && v < 1);
            }
    }
}

TEST(Importance, FlatIsZeroEdgesAreHighAndBadGuidesAreFar) {
    GeometryGuides g = stepGuides(30, 20, 2);
    ImportanceSettings s;
    s.sigmaNormal = 0.3f, s.sigmaPosition = AtrousSettings::kOff;
    std::vector<float> imp = geometryImportance(g, s);
    EXPECT_EQ(imp[5 * 30 + 4], 0.0f);        // inside the first wall
    EXPECT_GT(imp[5 * 30 + 10], 0.2f);       // at the first edge
    g.normal.set(5 * 30 + 4, std::nanf(""), 0, 0);
    imp = geometryImportance(g, s);
    EXPECT_GT(imp[5 * 30 + 4], 0.9f);        // alone: every neighbour reads as far
    EXPECT_TRUE(std::isfinite(imp[5 * 30 + 5]));
    s.window = 11;
    EXPECT_THROW(geometryImportance(g, s), Error);
}

TEST(Apportion, PropertiesOverRandomMapsAndBudgets) {
    for (std::uint64_t seed = 0; seed < 300; ++seed) {
        const Case c = randomCase(seed);
        const SampleCounts r = apportionSamples(c.importance, c.active, c.request);
        const std::size_t n = c.importance.size();
        std::int64_t active = 0;
        double wsum = 0;
        for (std::size_t i = 0; i < n; ++i)
            if (c.active.empty() || c.active[i]) ++active, wsum += c.importance[i];
        ASSERT_EQ(r.activePixels, active);
        if (active == 0) continue;
        ASSERT_EQ(sum(r.counts), c.request.budget) << "seed " << seed;
        const int m = r.minimum;
        ASSERT_EQ(m, std::min<std::int64_t>(c.request.minimum, c.request.budget / active));
        const double freeSamples = double(c.request.budget - std::int64_t(m) * active);
        // Quotas (in double): each count within one of minimum + quota, and
        // every pixel that got the extra sample had a fraction at least as
        // large as any pixel that did not.
        double minTaken = 2, maxLeft = -1;
        for (std::size_t i = 0; i < n; ++i) {
            if (!(c.active.empty() || c.active[i])) {
                ASSERT_EQ(r.counts[i], 0u);
                continue;
            }
            const double quota = wsum > 0 ? freeSamples * c.importance[i] / wsum : freeSamples / double(active);
            const double extra = double(r.counts[i]) - m - std::floor(quota);
            ASSERT_GE(r.counts[i], std::uint32_t(m));
            ASSERT_TRUE(std::abs(extra) < 1e-9 || std::abs(extra - 1) < 1e-9 || std::abs(quota - std::round(quota)) < 1e-6)
                << "seed " << seed << " pixel " << i << " quota " << quota << " count " << r.counts[i];
            const double frac = quota - std::floor(quota);
            if (extra > 0.5) minTaken = std::min(minTaken, frac);
            else maxLeft = std::max(maxLeft, frac);
        }
        ASSERT_GE(minTaken, maxLeft - 1e-6) << "seed " << seed;
    }
}

TEST(Apportion, DeterministicAndThreadIndependent) {
    Rng rng(7);
    std::vector<float> imp(400 * 300);
    for (float& v : imp) v = rng.uniform() < 0.5f ? 0.5f : rng.uniform();  // many ties
    const BudgetRequest req{4 * std::int64_t(imp.size()) + 12345, 1, 9};
    SampleCounts one, two, again;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = apportionSamples(imp, {}, req);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = apportionSamples(imp, {}, req);
        again = apportionSamples(imp, {}, req);
    }
    EXPECT_EQ(one.counts, two.counts);
    EXPECT_EQ(two.counts, again.counts);
    EXPECT_EQ(sum(one.counts), req.budget);
}

TEST(Apportion, BudgetBelowTheMinimumLowersItAndKeepsTheSum) {
    std::vector<float> imp(100);
    for (std::size_t i = 0; i < imp.size(); ++i) imp[i] = float(i) / 100;
    const SampleCounts r = apportionSamples(imp, {}, {250, 4, 0});  // 100 x 4 > 250
    EXPECT_EQ(r.minimum, 2);
    EXPECT_EQ(sum(r.counts), 250);
    for (std::uint32_t c : r.counts) EXPECT_GE(c, 2u);
    EXPECT_GT(r.counts[99], r.counts[1]);  // the rest follows importance
    const SampleCounts few = apportionSamples(imp, {}, {37, 1, 0});  // fewer samples than pixels
    EXPECT_EQ(few.minimum, 0);
    EXPECT_EQ(sum(few.counts), 37);
}

TEST(Apportion, AllZeroImportanceSpreadsUniformlyWithAHashedTieBreak) {
    const std::vector<float> imp(1000, 0.0f);
    const SampleCounts a = apportionSamples(imp, {}, {4100, 1, 1});
    const SampleCounts b = apportionSamples(imp, {}, {4100, 1, 2});
    EXPECT_EQ(sum(a.counts), 4100);
    int first100 = 0;
    for (std::size_t i = 0; i < imp.size(); ++i) {
        ASSERT_TRUE(a.counts[i] == 4 || a.counts[i] == 5);
        first100 += i < 100 && a.counts[i] == 5;
    }
    EXPECT_LT(first100, 40);  // the 100 extra samples are not all at the start
    EXPECT_NE(a.counts, b.counts);  // the tie seed decides which pixels
}

TEST(Apportion, NanAndInfinityAreReportedAndNothingIsLost) {
    std::vector<float> imp(50, 0.5f);
    imp[3] = std::nanf(""), imp[4] = -1.0f, imp[5] = -std::numeric_limits<float>::infinity();
    SampleCounts r = apportionSamples(imp, {}, {500, 2, 0});
    EXPECT_EQ(r.invalidImportance, 3);
    EXPECT_EQ(sum(r.counts), 500);
    EXPECT_EQ(r.counts[3], 2u);  // counted as zero importance: the minimum
    imp[7] = imp[9] = std::numeric_limits<float>::infinity();
    r = apportionSamples(imp, {}, {501, 2, 0});
    EXPECT_EQ(r.infiniteImportance, 2);
    EXPECT_EQ(sum(r.counts), 501);
    EXPECT_EQ(r.counts[7] + r.counts[9], 501u - 48 * 2);  // the infinite pixels share every free sample
    EXPECT_LE(std::max(r.counts[7], r.counts[9]) - std::min(r.counts[7], r.counts[9]), 1u);
    EXPECT_EQ(r.counts[8], 2u);
}

TEST(Apportion, EdgeBudgetsAndErrors) {
    const std::vector<float> imp = {0.1f, 0.9f, 0.0f};
    EXPECT_EQ(sum(apportionSamples(imp, {}, {0, 1, 0}).counts), 0);
    const SampleCounts none = apportionSamples(imp, {0, 0, 0}, {10, 1, 0});
    EXPECT_EQ(none.total, 0);  // nothing may take samples: reported, not hidden
    EXPECT_EQ(sum(none.counts), 0);
    const SampleCounts masked = apportionSamples(imp, {1, 0, 1}, {10, 1, 0});
    EXPECT_EQ(masked.counts[1], 0u);
    EXPECT_EQ(masked.counts[0] + masked.counts[2], 10u);
    EXPECT_THROW(apportionSamples(imp, {}, {-1, 1, 0}), Error);
    EXPECT_THROW(apportionSamples(imp, {}, {10, -1, 0}), Error);
    EXPECT_THROW(apportionSamples(imp, {1}, {10, 1, 0}), Error);
    EXPECT_THROW(apportionSamples({1.0f}, {}, {std::int64_t(1) << 33, 0, 0}), Error);  // one pixel, 2^33 samples
}

TEST(SampleBatches, EverySampleMapsToItsPixelOnceAcrossBatchBoundaries) {
    for (std::uint64_t seed = 0; seed < 40; ++seed) {
        Rng rng(seed + 100);
        std::vector<std::uint32_t> counts(1 + rng.next() % 500);
        for (auto& c : counts) c = rng.uniform() < 0.3f ? 0 : std::uint32_t(rng.next() % 9);
        const std::vector<std::int64_t> offsets = exclusiveScan(counts);
        ASSERT_EQ(offsets.size(), counts.size() + 1);
        std::vector<std::uint32_t> expected;  // pixel of every sample, in order
        for (std::size_t i = 0; i < counts.size(); ++i) {
            ASSERT_EQ(offsets[i], std::int64_t(expected.size()));
            expected.insert(expected.end(), counts[i], std::uint32_t(i));
        }
        ASSERT_EQ(offsets.back(), std::int64_t(expected.size()));
        const std::int64_t total = offsets.back();
        for (std::int64_t size : {std::int64_t(1), std::int64_t(7), std::int64_t(counts.size()), total + 5}) {
            const SampleBatches batches(offsets, size);
            ASSERT_EQ(batches.count(), (total + size - 1) / size);
            std::vector<std::uint32_t> all, buf;
            std::vector<std::uint32_t> seen(counts.size(), 0);
            for (std::int64_t b = 0; b < batches.count(); ++b) {
                batches.fill(b, buf);
                ASSERT_EQ(std::int64_t(buf.size()), std::min(size, total - b * size));
                for (std::size_t k = 0; k < buf.size(); ++k) {
                    const std::int64_t s = batches.begin(b) + std::int64_t(k);
                    ASSERT_EQ(batches.indexInPixel(s, buf[k]), seen[buf[k]]++);  // each pixel's samples in order
                }
                all.insert(all.end(), buf.begin(), buf.end());
            }
            ASSERT_EQ(all, expected) << "seed " << seed << " batch size " << size;
        }
    }
}

TEST(SampleBatches, LargeScanIsThreadIndependent) {
    Rng rng(5);
    std::vector<std::uint32_t> counts(200000);
    for (auto& c : counts) c = std::uint32_t(rng.next() % 5);
    std::vector<std::int64_t> a, b;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        a = exclusiveScan(counts);
    }
    b = exclusiveScan(counts);
    EXPECT_EQ(a, b);
    std::int64_t s = 0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
        ASSERT_EQ(b[i], s);
        s += counts[i];
    }
    EXPECT_THROW(SampleBatches(b, 0), Error);
}
