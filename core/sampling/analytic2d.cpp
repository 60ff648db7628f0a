#include "core/sampling/analytic2d.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "core/base/error.hpp"
#include "core/sampling/pattern_set.hpp"

namespace weft {

namespace {

using Polygon = std::vector<Vec2>;

// Sutherland-Hodgman against the half-plane a x + b y + c >= 0.
Polygon clip(const Polygon& in, double a, double b, double c) {
    Polygon out;
    for (std::size_t i = 0; i < in.size(); ++i) {
        const Vec2 &p = in[i], &q = in[(i + 1) % in.size()];
        const double fp = a * p.x + b * p.y + c, fq = a * q.x + b * q.y + c;
        if (fp >= 0) out.push_back(p);
        if ((fp >= 0) != (fq >= 0)) {
            const double s = fp / (fp - fq);
            out.push_back({p.x + s * (q.x - p.x), p.y + s * (q.y - p.y)});
        }
    }
    return out;
}

double area(const Polygon& p) {
    double s = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec2 &a = p[i], &b = p[(i + 1) % p.size()];
        s += a.x * b.y - b.x * a.y;
    }
    return 0.5 * std::abs(s);
}

Polygon box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

Polygon clipToBox(Polygon p, double x0, double y0, double x1, double y1) {
    p = clip(p, 1, 0, -x0);
    p = clip(p, -1, 0, x1);
    p = clip(p, 0, 1, -y0);
    return clip(p, 0, -1, y1);
}

// Integral of exp(i k u^2) over [a, b]: 16 panels of 8-point Gauss-Legendre
// (the phase turns by at most 2 pi per pixel in these scenes).
std::complex<double> chirpIntegral(double k, double a, double b) {
    static const double xs[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static const double ws[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    const int panels = 16;
    const double h = (b - a) / panels;
    std::complex<double> sum = 0;
    for (int p = 0; p < panels; ++p) {
        const double mid = a + (p + 0.5) * h, half = 0.5 * h;
        for (int i = 0; i < 4; ++i)
            for (double sgn : {-1.0, 1.0}) {
                const double u = mid + sgn * half * xs[i];
                sum += ws[i] * half * std::polar(1.0, k * u * u);
            }
    }
    return sum;
}

// Adaptive Simpson on [a, b] to an absolute tolerance.
template <class F>
double simpson(F f, double a, double fa, double m, double fm, double b, double fb, double whole, double tol, int depth) {
    const double lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = f(lm), frm = f(rm);
    const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
    if (depth <= 0 || std::abs(left + right - whole) <= 15 * tol) return left + right + (left + right - whole) / 15;
    return simpson(f, a, fa, lm, flm, m, fm, left, tol / 2, depth - 1) + simpson(f, m, fm, rm, frm, b, fb, right, tol / 2, depth - 1);
}

template <class F>
double integrate(F f, double a, double b, double tol) {
    if (b <= a) return 0;
    const double m = 0.5 * (a + b), fa = f(a), fm = f(m), fb = f(b);
    return simpson(f, a, fa, m, fm, b, fb, (b - a) / 6 * (fa + 4 * fm + fb), tol, 40);
}

// Integral of clamp(u / D, 0, 1) from -inf to u (for u > -inf the part below 0 is 0).
double rampIntegral(double u, double D) {
    if (u <= 0) return 0;
    if (u < D) return u * u / (2 * D);
    return u - D / 2;
}

}  // namespace

const char* analyticSceneNames() { return "zoneplate|grating|checker|siemens|lines|disc"; }

bool isAnalyticSceneName(const std::string& n) {
    return n == "zoneplate" || n == "grating" || n == "checker" || n == "siemens" || n == "lines" || n == "disc";
}

AnalyticScene analyticSceneFromName(const std::string& n) {
    if (n == "zoneplate") return AnalyticScene::ZonePlate;
    if (n == "grating") return AnalyticScene::Grating;
    if (n == "checker") return AnalyticScene::Checker;
    if (n == "siemens") return AnalyticScene::Siemens;
    if (n == "lines") return AnalyticScene::Lines;
    if (n == "disc") return AnalyticScene::Disc;
    throw Error("unknown analytic scene '" + n + "' (known: " + analyticSceneNames() + ")");
}

AnalyticImage::AnalyticImage(AnalyticScene scene, int width, int height)
    : scene_(scene), w_(width), h_(height), cx_(0.5 * width), cy_(0.5 * height) {
    zoneK_ = 4 * std::numbers::pi / width;
    horizon_ = 0.25 * height, focal_ = 0.5 * width;
    square_ = 16.0 / (0.75 * height);  // squares 16 pixels wide at the bottom edge
    farY_ = horizon_ + focal_ / (200 * square_);
    lineAngle_ = 6 * std::numbers::pi / 180;
    const double nx = -std::sin(lineAngle_), ny = std::cos(lineAngle_);
    const int lines = std::clamp(height / 4, 1, 12);  // at least 4 pixels apart: strips never overlap
    for (int i = 0; i < lines; ++i) {
        lineOffset_.push_back(nx * cx_ + ny * (i + 0.5) * height / lines);
        lineWidth_.push_back(lines > 1 ? 0.1 + 1.4 * i / (lines - 1) : 0.8);
    }
    discR_ = height / 6.0, discX0_ = 0.25 * width, discX1_ = 0.75 * width;
}

double AnalyticImage::checkerValue(double x, double y) const {
    if (y < farY_) return 0.5;
    const double Z = focal_ / (y - horizon_), X = (x - cx_) / focal_ * Z;
    return (long(std::floor(X / square_)) + long(std::floor(Z / square_))) % 2 == 0 ? 1.0 : 0.0;
}

double AnalyticImage::value(double x, double y, double t) const {
    switch (scene_) {
        case AnalyticScene::ZonePlate: {
            const double r2 = (x - cx_) * (x - cx_) + (y - cy_) * (y - cy_);
            return 0.5 + 0.5 * std::cos(zoneK_ * r2);
        }
        case AnalyticScene::Grating: return 0.5 + 0.5 * std::cos(2 * std::numbers::pi * (gratingFx_ * x + gratingFy_ * y));
        case AnalyticScene::Checker: return checkerValue(x, y);
        case AnalyticScene::Siemens: {
            double theta = std::atan2(y - cy_, x - cx_);
            if (theta < 0) theta += 2 * std::numbers::pi;
            return int(theta / (2 * std::numbers::pi / wedges_)) % 2 == 0 ? 1.0 : 0.0;
        }
        case AnalyticScene::Lines: {
            const double s = -std::sin(lineAngle_) * x + std::cos(lineAngle_) * y;
            for (std::size_t i = 0; i < lineOffset_.size(); ++i)
                if (std::abs(s - lineOffset_[i]) <= 0.5 * lineWidth_[i]) return 1.0;
            return 0.0;
        }
        case AnalyticScene::Disc: {
            const double c = discX0_ + t * (discX1_ - discX0_);
            return (x - c) * (x - c) + (y - cy_) * (y - cy_) < discR_ * discR_ ? 1.0 : 0.0;
        }
    }
    return 0;
}

double AnalyticImage::timeCoverage(double x, double y) const {
    const double dy = y - cy_, D = discX1_ - discX0_;
    if (std::abs(dy) >= discR_) return 0;
    const double a = std::sqrt(discR_ * discR_ - dy * dy);
    const double hi = std::clamp((x - discX0_ + a) / D, 0.0, 1.0), lo = std::clamp((x - discX0_ - a) / D, 0.0, 1.0);
    return hi - lo;
}

double AnalyticImage::checkerIntegral(int px, int py) const {
    const double y0 = std::max(double(py), farY_), y1 = py + 1.0;
    double sum = 0.5 * std::clamp(farY_ - py, 0.0, 1.0);  // sky
    if (y0 >= y1) return sum;
    const double zMin = focal_ / (y1 - horizon_), zMax = focal_ / (y0 - horizon_);
    const double u0 = (px - cx_) / focal_, u1 = (px + 1 - cx_) / focal_;
    const double xMin = std::min({u0 * zMin, u0 * zMax}), xMax = std::max({u1 * zMin, u1 * zMax});
    auto toScreen = [&](double X, double Z) { return Vec2{cx_ + focal_ * X / Z, horizon_ + focal_ / Z}; };
    for (long j = long(std::floor(zMin / square_)); j <= long(std::floor(zMax / square_)); ++j)
        for (long i = long(std::floor(xMin / square_)); i <= long(std::floor(xMax / square_)); ++i) {
            if ((i + j) % 2 != 0) continue;
            const double X0 = i * square_, X1 = X0 + square_, Z0 = std::max(j * square_, 1e-9), Z1 = (j + 1) * square_;
            const Polygon quad = {toScreen(X0, Z0), toScreen(X1, Z0), toScreen(X1, Z1), toScreen(X0, Z1)};
            sum += area(clipToBox(quad, px, y0, px + 1, y1));
        }
    return sum;
}

double AnalyticImage::discRowIntegral(double y, double x0, double x1) const {
    const double dy = y - cy_, D = discX1_ - discX0_;
    if (std::abs(dy) >= discR_) return 0;
    const double a = std::sqrt(discR_ * discR_ - dy * dy);
    auto ramp = [&](double s) { return rampIntegral(x1 - s, D) - rampIntegral(x0 - s, D); };
    return ramp(discX0_ - a) - ramp(discX0_ + a);
}

double AnalyticImage::discIntegral(int px, int py) const {
    // Split where the sqrt in a(y) makes the integrand non-smooth.
    std::vector<double> cuts = {double(py), double(py + 1)};
    for (double c : {cy_ - discR_, cy_ + discR_})
        if (c > py && c < py + 1) cuts.push_back(c);
    std::sort(cuts.begin(), cuts.end());
    double sum = 0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
        sum += integrate([&](double y) { return discRowIntegral(y, px, px + 1.0); }, cuts[i], cuts[i + 1], 1e-11);
    return sum;
}

double AnalyticImage::pixelIntegral(int px, int py) const {
    switch (scene_) {
        case AnalyticScene::ZonePlate: {
            const auto ix = chirpIntegral(zoneK_, px - cx_, px + 1 - cx_), iy = chirpIntegral(zoneK_, py - cy_, py + 1 - cy_);
            return 0.5 + 0.5 * (ix * iy).real();
        }
        case AnalyticScene::Grating: {
            // The mean of exp(2 pi i f.x) over a pixel: its value at the centre times sinc(fx) sinc(fy).
            auto sinc = [](double f) { return std::sin(std::numbers::pi * f) / (std::numbers::pi * f); };
            const double phase = 2 * std::numbers::pi * (gratingFx_ * (px + 0.5) + gratingFy_ * (py + 0.5));
            return 0.5 + 0.5 * std::cos(phase) * sinc(gratingFx_) * sinc(gratingFy_);
        }
        case AnalyticScene::Checker: return checkerIntegral(px, py);
        case AnalyticScene::Siemens: {
            const double alpha = 2 * std::numbers::pi / wedges_;
            double sum = 0;
            for (int k = 0; k < wedges_; k += 2) {
                const double a0 = k * alpha, a1 = a0 + alpha;
                Polygon p = clip(box(px, py, px + 1, py + 1), -std::sin(a0), std::cos(a0), std::sin(a0) * cx_ - std::cos(a0) * cy_);
                p = clip(p, std::sin(a1), -std::cos(a1), -std::sin(a1) * cx_ + std::cos(a1) * cy_);
                sum += area(p);
            }
            return sum;
        }
        case AnalyticScene::Lines: {
            const double nx = -std::sin(lineAngle_), ny = std::cos(lineAngle_);
            double sum = 0;
            for (std::size_t i = 0; i < lineOffset_.size(); ++i) {
                const double lo = lineOffset_[i] - 0.5 * lineWidth_[i], hi = lineOffset_[i] + 0.5 * lineWidth_[i];
                sum += area(clip(clip(box(px, py, px + 1, py + 1), nx, ny, -lo), -nx, -ny, hi));
            }
            return sum;
        }
        case AnalyticScene::Disc: return discIntegral(px, py);
    }
    return 0;
}

}  // namespace weft
