#pragma once
// Small helpers for point sets on the unit torus: wrapped differences and a
// bucket grid for neighbour queries (each query visits the cells within a
// ring, each cell once even when the ring wraps round the whole torus).
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/sampling/pattern_set.hpp"

namespace weft {

// Signed difference a - b wrapped into [-0.5, 0.5).
inline double torusDelta(double a, double b) {
    double d = a - b;
    return d - std::floor(d + 0.5);
}

inline double torusDistanceSq(const Vec2& a, const Vec2& b) {
    const double dx = torusDelta(a.x, b.x), dy = torusDelta(a.y, b.y);
    return dx * dx + dy * dy;
}

// Points bucketed by cell (compressed rows: cellStart[c]..cellStart[c+1]).
class TorusBuckets {
public:
    TorusBuckets(const std::vector<Vec2>& points, int resolution) : res_(std::max(1, resolution)) {
        cellStart_.assign(std::size_t(res_) * res_ + 1, 0);
        for (const Vec2& p : points) ++cellStart_[cellOf(p) + 1];
        for (std::size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
        items_.resize(points.size());
        std::vector<int> fill(cellStart_.begin(), cellStart_.end() - 1);
        for (int i = 0; i < int(points.size()); ++i) items_[fill[cellOf(points[i])]++] = i;
    }
    int resolution() const { return res_; }
    int cellCoord(double v) const { return std::min(int(v * res_), res_ - 1); }
    int cellOf(const Vec2& p) const { return cellCoord(p.y) * res_ + cellCoord(p.x); }

    // fn(index) for every point in cells within `ring` cells of p's cell.
    template <class Fn>
    void forEachNear(const Vec2& p, int ring, Fn fn) const {
        const int cx = cellCoord(p.x), cy = cellCoord(p.y);
        const bool all = 2 * ring + 1 >= res_;
        const int lo = all ? 0 : -ring, hi = all ? res_ - 1 : ring;
        for (int dy = lo; dy <= hi; ++dy) {
            const int y = all ? dy : (cy + dy + res_) % res_;
            for (int dx = lo; dx <= hi; ++dx) {
                const int x = all ? dx : (cx + dx + res_) % res_;
                const int c = y * res_ + x;
                for (int k = cellStart_[c]; k < cellStart_[c + 1]; ++k) fn(items_[k]);
            }
        }
    }

private:
    int res_;
    std::vector<int> cellStart_, items_;
};

}  // namespace weft
