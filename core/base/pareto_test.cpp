// Pareto front: checked against the definition on random sets with ties and
// NaNs, plus hand cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/pareto.hpp"
#include "core/base/rng.hpp"

using namespace weft;

namespace {

using Points = std::vector<std::pair<double, double>>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool hasNaN(const std::pair<double, double>& p) { return std::isnan(p.first) || std::isnan(p.second); }

// The definition, O(n^2): not NaN and dominated by no point.
std::vector<std::size_t> bruteFront(const Points& pts) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        bool dominated = hasNaN(pts[i]);
        for (const auto& q : pts) dominated = dominated || (!hasNaN(q) && dominates(q, pts[i]));
        if (!dominated) out.push_back(i);
    }
    return out;
}

// 1..50 points on a coarse grid (many ties in each coordinate and exact
// duplicates), about one in twenty with a NaN coordinate.
Points randomPoints(std::uint64_t seed) {
    Rng rng(seed);
    Points pts(1 + rng.next() % 50);
    for (auto& [c, e] : pts) {
        c = static_cast<double>(rng.next() % 8), e = static_cast<double>(rng.next() % 8);
        if (rng.next() % 20 == 0) (rng.next() % 2 ? c : e) = kNaN;
    }
    return pts;
}

}  // namespace

TEST(Pareto, RandomSetsMatchTheDefinition) {
    for (std::uint64_t seed = 0; seed < 200; ++seed) {
        const Points pts = randomPoints(seed);
        const std::vector<std::size_t> front = paretoFront(pts);
        std::vector<bool> onFront(pts.size(), false);
        for (std::size_t i : front) onFront[i] = true;
        for (std::size_t i : front) {
            ASSERT_FALSE(hasNaN(pts[i])) << "seed " << seed;
            for (const auto& q : pts) ASSERT_FALSE(!hasNaN(q) && dominates(q, pts[i])) << "seed " << seed;
        }
        for (std::size_t i = 0; i < pts.size(); ++i) {
            if (onFront[i] || hasNaN(pts[i])) continue;
            auto beats = [&](std::size_t f) { return dominates(pts[f], pts[i]); };
            ASSERT_TRUE(std::any_of(front.begin(), front.end(), beats)) << "seed " << seed << " point " << i;
        }
        std::vector<std::size_t> sorted = front;
        std::sort(sorted.begin(), sorted.end());
        ASSERT_EQ(sorted, bruteFront(pts)) << "seed " << seed;
        for (std::size_t k = 1; k < front.size(); ++k) {
            ASSERT_LE(pts[front[k - 1]].first, pts[front[k]].first) << "seed " << seed;
            ASSERT_GE(pts[front[k - 1]].second, pts[front[k]].second) << "seed " << seed;
        }
    }
}

TEST(Pareto, Empty) { EXPECT_TRUE(paretoFront({}).empty()); }

TEST(Pareto, Single) { EXPECT_EQ(paretoFront({{3, 4}}), std::vector<std::size_t>{0}); }

TEST(Pareto, AllEqualAreAllKept) {
    EXPECT_EQ(paretoFront({{2, 2}, {2, 2}, {2, 2}}), (std::vector<std::size_t>{0, 1, 2}));
}

TEST(Pareto, StaircaseWithDominatedPoints) {
    // Front: (1,9) (2,5) (4,4) (7,1); the rest each lose to one of them.
    const Points pts{{7, 1}, {3, 6}, {1, 9}, {4, 4}, {2, 5}, {8, 1}, {4, 5}, {2, 9}};
    EXPECT_EQ(paretoFront(pts), (std::vector<std::size_t>{2, 4, 3, 0}));
}

TEST(Pareto, EqualCostKeepsOnlyTheLowestError) {
    EXPECT_EQ(paretoFront({{1, 3}, {1, 2}, {1, 5}}), std::vector<std::size_t>{1});
    EXPECT_EQ(paretoFront({{3, 1}, {2, 1}, {5, 1}}), std::vector<std::size_t>{1});
}

TEST(Pareto, DuplicatesOfAFrontPointSortByIndex) {
    EXPECT_EQ(paretoFront({{5, 0}, {1, 2}, {0, 9}, {1, 2}}), (std::vector<std::size_t>{2, 1, 3, 0}));
}

TEST(Pareto, NaNIsNeverOnTheFront) {
    EXPECT_EQ(paretoFront({{kNaN, 0}, {1, kNaN}, {2, 2}}), std::vector<std::size_t>{2});
    EXPECT_TRUE(paretoFront({{kNaN, kNaN}}).empty());
}

TEST(Pareto, InfinitiesAreOrdinaryValues) {
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(paretoFront({{inf, 0}, {0, inf}, {1, 1}, {inf, inf}}), (std::vector<std::size_t>{1, 2, 0}));
}
