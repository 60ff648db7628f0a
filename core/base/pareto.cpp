#include "core/base/pareto.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace weft {

bool dominates(const std::pair<double, double>& a, const std::pair<double, double>& b) {
    return a.first <= b.first && a.second <= b.second && (a.first < b.first || a.second < b.second);
}

// One sort and one sweep. Sorted by (cost, error, index), a point can only be
// dominated by one before it, and the front's last point has the least error
// of those (at the least cost for that error), so it alone decides.
std::vector<std::size_t> paretoFront(const std::vector<std::pair<double, double>>& costAndError) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < costAndError.size(); ++i)
        if (!std::isnan(costAndError[i].first) && !std::isnan(costAndError[i].second)) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return std::tie(costAndError[a], a) < std::tie(costAndError[b], b);
    });
    std::vector<std::size_t> front;
    for (std::size_t i : order) {
        if (front.empty() || !dominates(costAndError[front.back()], costAndError[i])) front.push_back(i);
    }
    return front;
}

}  // namespace weft
