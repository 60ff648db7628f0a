// lloyd: Monte-Carlo Lloyd relaxation on the torus (Keller & Heidrich 2001,
// appendix). Start from uniform random points; each iteration draws
// `oversample` uniform samples per point, gives each sample to its nearest
// point on the torus, and moves every point to the mean of its samples
// (the estimated centroid of its Voronoi cell). The result is blue noise
// whose nearest-neighbour distances are bounded from below and above, and it
// tiles seamlessly because all distances wrap.
#include <cmath>
#include <limits>

#include "core/base/rng.hpp"
#include "core/sampling/generators.hpp"
#include "core/sampling/torus.hpp"

namespace weft {

namespace {

// Index of the point nearest to q, growing the searched ring of cells until
// nothing outside it can be nearer.
int nearest(const TorusBuckets& buckets, const std::vector<Vec2>& points, const Vec2& q) {
    const double side = 1.0 / buckets.resolution();
    int best = -1;
    double bestSq = std::numeric_limits<double>::infinity();
    for (int ring = 1;; ++ring) {
        buckets.forEachNear(q, ring, [&](int i) {
            const double d = torusDistanceSq(q, points[i]);
            if (d < bestSq || (d == bestSq && i < best)) bestSq = d, best = i;
        });
        const double safe = ring * side;  // every unsearched point is at least this far
        if ((best >= 0 && bestSq <= safe * safe) || 2 * ring + 1 >= buckets.resolution()) return best;
    }
}

void relaxOnce(std::vector<Vec2>& points, int oversample, std::uint64_t seed) {
    const int n = int(points.size());
    const TorusBuckets buckets(points, std::max(1, int(std::sqrt(double(n)))));
    std::vector<Vec2> sum(n);
    std::vector<int> hits(n, 0);
    Rng rng(seed);
    for (long s = 0; s < long(n) * oversample; ++s) {
        const Vec2 q{rng.uniformDouble(), rng.uniformDouble()};
        const int i = nearest(buckets, points, q);
        sum[i].x += torusDelta(q.x, points[i].x), sum[i].y += torusDelta(q.y, points[i].y);
        ++hits[i];
    }
    for (int i = 0; i < n; ++i) {
        if (!hits[i]) continue;
        const double x = points[i].x + sum[i].x / hits[i], y = points[i].y + sum[i].y / hits[i];
        points[i] = {x - std::floor(x), y - std::floor(y)};
    }
}

std::vector<Vec2> lloyd(int count, int iterations, int oversample, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Vec2> points(count);
    for (Vec2& p : points) p.x = rng.uniformDouble(), p.y = rng.uniformDouble();
    for (int k = 0; k < iterations; ++k) relaxOnce(points, oversample, hashCombine(seed, std::uint64_t(k) + 1));
    return points;
}

}  // namespace

void registerLloydGenerator(PatternGeneratorRegistry& r) {
    r.add({"lloyd", "Monte-Carlo Lloyd relaxation on the torus (blue noise that tiles seamlessly)",
           ParamTable("pattern lloyd",
                      {intParam("iterations", 20, 0, 1000, "relaxation steps"),
                       intParam("oversample", 64, 1, 100000, "uniform samples per point to estimate each Voronoi cell")}),
           [](int count, const ParamSet& o, std::uint64_t seed) {
               return lloyd(count, int(o.getInt("iterations")), int(o.getInt("oversample")), seed);
           }});
}

}  // namespace weft
