#pragma once
// Measures of a point set on the unit square/torus: L2-star discrepancy
// (Warnock's closed form), nearest-neighbour distances on the torus, and the
// periodogram (power spectrum of the point set, averaged over seeds) with its
// radial average.
#include <vector>

#include "core/sampling/pattern_set.hpp"

namespace weft {

// Warnock: T^2 = 1/9 - 2/N sum_i prod_k (1 - x_ik^2)/2
//               + 1/N^2 sum_i sum_j prod_k (1 - max(x_ik, x_jk)).  O(N^2).
double l2StarDiscrepancy(const std::vector<Vec2>& points);
// The same in one dimension (the x coordinates), for the 1D checks.
double l2StarDiscrepancy1D(const std::vector<double>& xs);

struct NeighbourDistances {
    double min = 0, mean = 0, max = 0;  // of every point's nearest-neighbour distance
};
// Toroidal nearest-neighbour distances (at least two points).
NeighbourDistances neighbourDistances(const std::vector<Vec2>& points);

// |sum_k exp(-2 pi i f . x_k)|^2 / N for integer f in [-R, R]^2, row-major
// (2R+1)^2 with fy outer; f = 0 is at (R, R). Deterministic and threaded.
std::vector<double> periodogram(const std::vector<Vec2>& points, int R);

struct RadialBin {
    int radius = 0;        // |f| rounded
    double power = 0;      // mean periodogram value in the ring
    double anisotropy = 0; // variance / mean^2 in the ring (0: isotropic)
    int count = 0;
};
// Rings 1..R (DC excluded) of a (2R+1)^2 periodogram.
std::vector<RadialBin> radialAverage(const std::vector<double>& spectrum, int R);

}  // namespace weft
