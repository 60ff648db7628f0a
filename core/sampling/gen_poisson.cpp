// poisson: Poisson-disk points by dart throwing on the unit torus (Wolberg
// 6.3.2). A uniform dart is kept when no kept point lies closer than the
// radius. The radius is `radius` times the distance of count points in a
// hexagonal packing; dart throwing jams near 0.76 of it. If `patience` darts
// in a row all fail, the radius shrinks by 2% (reported by weft pattern) so
// exactly count points always result.
//
// The grid-accelerated test (accel=grid, the default) buckets kept points in
// cells of side <= radius / sqrt(2) and checks only nearby cells; accel=none
// checks every kept point. Both take the same decisions on the same darts.
#include <cmath>
#include <memory>

#include "core/base/rng.hpp"
#include "core/sampling/generators.hpp"
#include "core/sampling/torus.hpp"

namespace weft {

namespace {

constexpr int kPatience = 4000;

// Kept points in cells holding at most one point each (cell side <= r / sqrt 2).
class DiskGrid {
public:
    explicit DiskGrid(double radius) : radius_(radius), res_(int(std::floor(std::sqrt(2.0) / radius)) + 1) {
        ring_ = int(std::ceil(radius * res_));
        cells_.assign(std::size_t(res_) * res_, -1);
    }
    int cellOf(const Vec2& p) const {
        return std::min(int(p.y * res_), res_ - 1) * res_ + std::min(int(p.x * res_), res_ - 1);
    }
    bool farFromAll(const Vec2& p, const std::vector<Vec2>& kept) const {
        const int cx = std::min(int(p.x * res_), res_ - 1), cy = std::min(int(p.y * res_), res_ - 1);
        const double r2 = radius_ * radius_;
        const bool all = 2 * ring_ + 1 >= res_;
        const int lo = all ? 0 : -ring_, hi = all ? res_ - 1 : ring_;
        for (int dy = lo; dy <= hi; ++dy) {
            const int row = (all ? dy : (cy + dy + res_) % res_) * res_;
            for (int dx = lo; dx <= hi; ++dx) {
                const int k = cells_[row + (all ? dx : (cx + dx + res_) % res_)];
                if (k >= 0 && torusDistanceSq(p, kept[k]) < r2) return false;
            }
        }
        return true;
    }
    void insert(const Vec2& p, int index) { cells_[cellOf(p)] = index; }

private:
    double radius_;
    int res_, ring_ = 1;
    std::vector<int> cells_;
};

bool farFromAllPlain(const Vec2& p, const std::vector<Vec2>& kept, double radius) {
    for (const Vec2& q : kept)
        if (torusDistanceSq(p, q) < radius * radius) return false;
    return true;
}

}  // namespace

PoissonResult poissonDartThrowing(int count, double relativeRadius, std::uint64_t seed, bool useGrid) {
    PoissonResult out;
    out.radius = relativeRadius * hexagonalDistance(count);
    out.points.reserve(count);
    Rng rng(seed);
    auto grid = std::make_unique<DiskGrid>(out.radius);
    int failures = 0;
    while (int(out.points.size()) < count) {
        const Vec2 dart{rng.uniformDouble(), rng.uniformDouble()};
        ++out.darts;
        const bool ok = useGrid ? grid->farFromAll(dart, out.points) : farFromAllPlain(dart, out.points, out.radius);
        if (ok) {
            if (useGrid) grid->insert(dart, int(out.points.size()));
            out.points.push_back(dart);
            failures = 0;
        } else if (++failures == kPatience) {
            out.radius *= 0.98, failures = 0;
            if (useGrid) {
                grid = std::make_unique<DiskGrid>(out.radius);
                for (int i = 0; i < int(out.points.size()); ++i) grid->insert(out.points[i], i);
            }
        }
    }
    return out;
}

void registerPoissonGenerator(PatternGeneratorRegistry& r) {
    r.add({"poisson", "Poisson-disk points by dart throwing with a minimum toroidal distance",
           ParamTable("pattern poisson",
                      {floatParam("radius", 0.65, 0.01, 0.76,
                                  "minimum distance as a fraction of the hexagonal-packing distance"),
                       enumParam("accel", "grid", {"grid", "none"},
                                 "grid: bucketed distance test; none: test every kept point (same points, slower)")}),
           [](int count, const ParamSet& o, std::uint64_t seed) {
               return poissonDartThrowing(count, o.getFloat("radius"), seed, o.getString("accel") == "grid").points;
           }});
}

}  // namespace weft
