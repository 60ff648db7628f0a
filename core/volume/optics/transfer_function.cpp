#include "core/volume/optics/transfer_function.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/error.hpp"

namespace weft {

TransferFunction::TransferFunction(double rangeMin, double rangeMax, std::vector<TfPoint> points)
    : rangeMin_(rangeMin), rangeMax_(rangeMax), points_(std::move(points)) {
    if (points_.empty()) throw Error("transfer function: needs at least one point");
    if (!(rangeMax_ > rangeMin_) || !std::isfinite(rangeMin_) || !std::isfinite(rangeMax_))
        throw Error("transfer function: range must be finite with max > min");
    buildTable();
}

TfPoint TransferFunction::atS(double s) const {
    if (s <= points_.front().s) return points_.front();
    if (s >= points_.back().s) return points_.back();
    auto hi = std::upper_bound(points_.begin(), points_.end(), s, [](double v, const TfPoint& p) { return v < p.s; });
    const TfPoint& b = *hi;
    const TfPoint& a = *(hi - 1);
    const double t = b.s > a.s ? (s - a.s) / (b.s - a.s) : 0.0;
    TfPoint out;
    out.s = s;
    for (int c = 0; c < 3; ++c) out.color[c] = a.color[c] + t * (b.color[c] - a.color[c]);
    out.extinction = a.extinction + t * (b.extinction - a.extinction);
    return out;
}

void TransferFunction::buildTable() {
    table_.resize(kTableSize + 1);
    for (int i = 0; i <= kTableSize; ++i) {
        const TfPoint p = atS(double(i) / kTableSize);
        table_[i] = {float(p.color[0]), float(p.color[1]), float(p.color[2]), float(p.extinction)};
    }
    visibleBefore_.assign(kTableSize + 2, 0);
    for (int i = 0; i <= kTableSize; ++i) visibleBefore_[i + 1] = visibleBefore_[i] + (table_[i].extinction != 0.0f);
    tableScale_ = float(kTableSize / (rangeMax_ - rangeMin_));
    tableOffset_ = float(-rangeMin_ * kTableSize / (rangeMax_ - rangeMin_));
}

std::array<double, 2> TransferFunction::extinctionBounds(double lo, double hi) const {
    const double s0 = normalize(std::min(lo, hi)), s1 = normalize(std::max(lo, hi));
    double emin = std::min(atS(s0).extinction, atS(s1).extinction), emax = std::max(atS(s0).extinction, atS(s1).extinction);
    for (const TfPoint& p : points_)
        if (p.s > s0 && p.s < s1) emin = std::min(emin, p.extinction), emax = std::max(emax, p.extinction);
    return {emin, emax};
}

double TransferFunction::zeroExtinctionBelow() const {
    for (std::size_t i = 0; i < points_.size(); ++i)
        if (points_[i].extinction != 0)  // NaN counts as absorbing
            return i == 0 ? 0.0 : points_[i - 1].s;
    return std::numeric_limits<double>::infinity();
}

TransferFunction TransferFunction::defaultFor(double minValue, double maxValue) {
    const double lo = std::min(0.0, minValue);
    const double hi = maxValue > lo ? maxValue : lo + 1.0;
    // Thin wisps bluish grey, dense cores warm white; extinction grows with density.
    return TransferFunction(lo, hi,
                            {{0.0, {0.35, 0.45, 0.65}, 0.0},
                             {0.15, {0.75, 0.75, 0.8}, 0.08},
                             {1.0, {1.0, 0.85, 0.65}, 0.6}});
}

}  // namespace weft
