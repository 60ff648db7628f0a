#pragma once
// Pareto front of (cost, error) points, both minimised: what `weft sweep`
// and `weft tune` report as the settings worth choosing between.
#include <cstddef>
#include <utility>
#include <vector>

namespace weft {

// a dominates b: no worse in both coordinates and better in at least one.
bool dominates(const std::pair<double, double>& a, const std::pair<double, double>& b);

// Indices of the points no other point dominates, sorted by cost (then by
// index). Exact duplicates do not dominate each other, so all copies of a
// front point are kept: every point left off is dominated by one on the
// front. Points with a NaN coordinate are never on the front.
std::vector<std::size_t> paretoFront(const std::vector<std::pair<double, double>>& costAndError);

}  // namespace weft
