#include "core/sampling/pattern_analysis.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "core/base/error.hpp"
#include "core/sampling/torus.hpp"

namespace weft {

namespace {

// Sums values[i] in index order, so the total does not depend on threading.
double orderedSum(const std::vector<double>& values) {
    double s = 0;
    for (double v : values) s += v;
    return s;
}

}  // namespace

double l2StarDiscrepancy(const std::vector<Vec2>& p) {
    const std::size_t n = p.size();
    if (n == 0) throw Error("discrepancy of an empty point set");
    std::vector<double> rows(n), singles(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            double s = 0;
            for (std::size_t j = 0; j < n; ++j) s += (1 - std::max(p[i].x, p[j].x)) * (1 - std::max(p[i].y, p[j].y));
            rows[i] = s;
            singles[i] = 0.25 * (1 - p[i].x * p[i].x) * (1 - p[i].y * p[i].y);
        }
    });
    const double N = double(n);
    const double t2 = 1.0 / 9.0 - 2.0 / N * orderedSum(singles) + orderedSum(rows) / (N * N);
    return std::sqrt(std::max(t2, 0.0));
}

double l2StarDiscrepancy1D(const std::vector<double>& xs) {
    const double N = double(xs.size());
    double single = 0, pair = 0;
    for (double a : xs) {
        single += 0.5 * (1 - a * a);
        for (double b : xs) pair += 1 - std::max(a, b);
    }
    return std::sqrt(std::max(1.0 / 3.0 - 2.0 / N * single + pair / (N * N), 0.0));
}

NeighbourDistances neighbourDistances(const std::vector<Vec2>& points) {
    const int n = int(points.size());
    if (n < 2) throw Error("nearest-neighbour distances need at least two points");
    const TorusBuckets buckets(points, std::max(1, int(std::sqrt(double(n)))));
    const double side = 1.0 / buckets.resolution();
    std::vector<double> nn(n);
    tbb::parallel_for(0, n, [&](int i) {
        double best = std::numeric_limits<double>::infinity();
        for (int ring = 1;; ++ring) {
            buckets.forEachNear(points[i], ring, [&](int j) {
                if (j != i) best = std::min(best, torusDistanceSq(points[i], points[j]));
            });
            if (best <= (ring * side) * (ring * side) || 2 * ring + 1 >= buckets.resolution()) break;
        }
        nn[i] = std::sqrt(best);
    });
    NeighbourDistances d{nn[0], 0, nn[0]};
    for (double v : nn) d.min = std::min(d.min, v), d.max = std::max(d.max, v);
    d.mean = orderedSum(nn) / n;
    return d;
}

std::vector<double> periodogram(const std::vector<Vec2>& points, int R) {
    const int side = 2 * R + 1;
    const std::size_t n = points.size();
    // e^{-2 pi i k x} for k = -R..R, per point and axis.
    std::vector<std::complex<double>> ex(n * side), ey(n * side);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t k) {
        for (int f = -R; f <= R; ++f) {
            ex[k * side + f + R] = std::polar(1.0, -2 * std::numbers::pi * f * points[k].x);
            ey[k * side + f + R] = std::polar(1.0, -2 * std::numbers::pi * f * points[k].y);
        }
    });
    std::vector<double> out(std::size_t(side) * side);
    tbb::parallel_for(0, side, [&](int fy) {
        std::vector<std::complex<double>> row(side);
        for (std::size_t k = 0; k < n; ++k) {
            const std::complex<double> y = ey[k * side + fy];
            const std::complex<double>* x = &ex[k * side];
            for (int fx = 0; fx < side; ++fx) row[fx] += x[fx] * y;
        }
        for (int fx = 0; fx < side; ++fx) out[std::size_t(fy) * side + fx] = std::norm(row[fx]) / double(n);
    });
    return out;
}

std::vector<RadialBin> radialAverage(const std::vector<double>& spectrum, int R) {
    const int side = 2 * R + 1;
    std::vector<RadialBin> bins(R + 1);
    std::vector<double> sum(R + 1, 0), sumSq(R + 1, 0);
    for (int fy = -R; fy <= R; ++fy)
        for (int fx = -R; fx <= R; ++fx) {
            const int r = int(std::lround(std::sqrt(double(fx * fx + fy * fy))));
            if (r < 1 || r > R) continue;
            const double v = spectrum[std::size_t(fy + R) * side + fx + R];
            sum[r] += v, sumSq[r] += v * v, ++bins[r].count;
        }
    for (int r = 1; r <= R; ++r) {
        RadialBin& b = bins[r];
        b.radius = r;
        b.power = sum[r] / b.count;
        const double var = sumSq[r] / b.count - b.power * b.power;
        b.anisotropy = b.power > 0 ? std::max(var, 0.0) / (b.power * b.power) : 0;
    }
    bins.erase(bins.begin());
    return bins;
}

}  // namespace weft
