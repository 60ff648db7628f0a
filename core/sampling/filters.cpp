#include "core/sampling/filters.hpp"

#include <cmath>
#include <numbers>

#include "core/base/error.hpp"

namespace weft {

namespace {

// Mitchell-Netravali cubic on t in [-2, 2]; integrates to 1 for any B, C.
double mitchellNetravali(double t, double B, double C) {
    t = std::abs(t);
    if (t < 1) return ((12 - 9 * B - 6 * C) * t * t * t + (-18 + 12 * B + 6 * C) * t * t + (6 - 2 * B)) / 6;
    if (t < 2) return ((-B - 6 * C) * t * t * t + (6 * B + 30 * C) * t * t + (-12 * B - 48 * C) * t + (8 * B + 24 * C)) / 6;
    return 0;
}

}  // namespace

ReconstructionFilter::ReconstructionFilter(FilterKind kind, double radius)
    : kind_(kind), radius_(radius > 0 ? radius : defaultRadius(kind)) {
    if (kind_ == FilterKind::Gaussian) {
        // Truncated at 3 sigma and shifted to reach 0 at the edge, then normalised.
        gaussSigma_ = radius_ / 3;
        gaussEdge_ = std::exp(-0.5 * 9.0);
        const double full = gaussSigma_ * std::sqrt(2 * std::numbers::pi) * std::erf(3.0 / std::sqrt(2.0));
        gaussNorm_ = 1.0 / (full - 2 * radius_ * gaussEdge_);
    }
}

double ReconstructionFilter::eval1D(double x) const {
    const double a = std::abs(x), r = radius_;
    if (a >= r) return 0;
    switch (kind_) {
        case FilterKind::Box: return 1 / (2 * r);
        case FilterKind::Tent: return (1 - a / r) / r;
        case FilterKind::Gaussian: return (std::exp(-0.5 * (a * a) / (gaussSigma_ * gaussSigma_)) - gaussEdge_) * gaussNorm_;
        case FilterKind::Mitchell: return mitchellNetravali(2 * a / r, 1.0 / 3, 1.0 / 3) * 2 / r;
        case FilterKind::BSpline: return mitchellNetravali(2 * a / r, 1.0, 0.0) * 2 / r;
        case FilterKind::RaisedCosine: return (1 + std::cos(std::numbers::pi * a / r)) / (2 * r);
    }
    return 0;
}

double ReconstructionFilter::defaultRadius(FilterKind kind) {
    switch (kind) {
        case FilterKind::Box: return 0.5;
        case FilterKind::Tent: return 1.0;
        case FilterKind::Gaussian: return 1.5;
        case FilterKind::Mitchell: return 2.0;
        case FilterKind::BSpline: return 2.0;
        case FilterKind::RaisedCosine: return 1.0;
    }
    return 0.5;
}

const char* ReconstructionFilter::names() { return "box|tent|gaussian|mitchell|bspline|raised_cosine"; }

FilterKind ReconstructionFilter::kindFromName(const std::string& n) {
    if (n == "box") return FilterKind::Box;
    if (n == "tent") return FilterKind::Tent;
    if (n == "gaussian") return FilterKind::Gaussian;
    if (n == "mitchell") return FilterKind::Mitchell;
    if (n == "bspline") return FilterKind::BSpline;
    if (n == "raised_cosine") return FilterKind::RaisedCosine;
    throw Error("unknown filter '" + n + "' (known: " + names() + ")");
}

}  // namespace weft
