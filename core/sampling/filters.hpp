#pragma once
// Reconstruction filters (Wolberg 6.3.3, 6.3.6): box, tent, Gaussian,
// Mitchell-Netravali (B = C = 1/3), cubic B-spline and raised cosine. Each
// 1D kernel is normalised to integrate to 1 over its support [-r, r]; the 2D
// filter is the separable product. Irregular samples are reconstructed by the
// weighted average sum h(x - x_k) f(x_k) / sum h(x - x_k) (eq. 6.3.2).
#include <string>

namespace weft {

enum class FilterKind { Box, Tent, Gaussian, Mitchell, BSpline, RaisedCosine };

class ReconstructionFilter {
public:
    // radius <= 0 takes the kind's customary radius (in pixels).
    explicit ReconstructionFilter(FilterKind kind = FilterKind::Box, double radius = 0);

    FilterKind kind() const { return kind_; }
    double radius() const { return radius_; }
    double eval1D(double x) const;
    double eval(double dx, double dy) const { return eval1D(dx) * eval1D(dy); }

    static double defaultRadius(FilterKind kind);
    static FilterKind kindFromName(const std::string& name);  // error lists the names
    static const char* names();                               // "box|tent|..."

private:
    FilterKind kind_;
    double radius_;
    double gaussSigma_ = 0, gaussEdge_ = 0, gaussNorm_ = 1;
};

}  // namespace weft
