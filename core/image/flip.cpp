#include "core/image/flip.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/base/error.hpp"

namespace weft {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95;  // q_f = 0.5 is a square root
constexpr double kFeatureWidthDeg = 0.082;  // w: sigma = w/2 degrees

// One channel of an image, row-major.
struct Plane {
    int w = 0, h = 0;
    std::vector<float> v;
    Plane(int width, int height) : w(width), h(height), v(static_cast<std::size_t>(width) * height, 0.0f) {}
    float& at(int x, int y) { return v[static_cast<std::size_t>(y) * w + x]; }
    float at(int x, int y) const { return v[static_cast<std::size_t>(y) * w + x]; }
};

using Kernel = std::vector<double>;  // odd length, centred on the middle tap
using Vec3 = std::array<double, 3>;
using Mat3 = std::array<Vec3, 3>;

// Linear sRGB (Rec.709 primaries, D65) to CIE XYZ, and back.
constexpr Mat3 kRgbToXyz{{{0.4124564, 0.3575761, 0.1804375},
                          {0.2126729, 0.7151522, 0.0721750},
                          {0.0193339, 0.1191920, 0.9503041}}};
constexpr Mat3 kXyzToRgb{{{3.2404542, -1.5371385, -0.4985314},
                          {-0.9692660, 1.8760108, 0.0415560},
                          {0.0556434, -0.2040259, 1.0572252}}};

Vec3 mul(const Mat3& m, const Vec3& v) {
    Vec3 r{};
    for (int i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    return r;
}

// XYZ divided by the white point (the XYZ of RGB 1, 1, 1).
Vec3 rgbToRelXyz(const Vec3& rgb) {
    static const Vec3 white = mul(kRgbToXyz, {1, 1, 1});
    const Vec3 xyz = mul(kRgbToXyz, rgb);
    return {xyz[0] / white[0], xyz[1] / white[1], xyz[2] / white[2]};
}

Vec3 relXyzToRgb(const Vec3& rel) {
    static const Vec3 white = mul(kRgbToXyz, {1, 1, 1});
    return mul(kXyzToRgb, {rel[0] * white[0], rel[1] * white[1], rel[2] * white[2]});
}

// YCxCz: CIELAB without the cube root, so it is linear and may be filtered.
Vec3 relXyzToYcxcz(const Vec3& x) { return {116 * x[1] - 16, 500 * (x[0] - x[1]), 200 * (x[1] - x[2])}; }

Vec3 ycxczToRelXyz(const Vec3& c) {
    const double y = (c[0] + 16) / 116;
    return {y + c[1] / 500, y, y - c[2] / 200};
}

double labF(double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

// CIELAB with the Hunt adjustment (chroma scaled by L/100): dark colours differ less.
Vec3 huntLab(const Vec3& rgb) {
    const Vec3 x = rgbToRelXyz(rgb);
    const double fx = labF(x[0]), fy = labF(x[1]), fz = labF(x[2]);
    const double L = 116 * fy - 16;
    return {L, 0.01 * L * 500 * (fx - fy), 0.01 * L * 200 * (fy - fz)};
}

// HyAB: city-block in lightness, Euclidean in chroma (large differences).
// Lab values of colours in [0, 1] are bounded (|a|, |b| < 500): the plain root cannot overflow, and is faster than hypot.
double hyab(const Vec3& a, const Vec3& b) {
    const double da = a[1] - b[1], db = a[2] - b[2];
    return std::abs(a[0] - b[0]) + std::sqrt(da * da + db * db);
}

// The largest colour error, green vs blue, after the power q_c.
double maxColorError() {
    static const double cmax = std::pow(hyab(huntLab({0, 1, 0}), huntLab({0, 0, 1})), kQc);
    return cmax;
}

// Compresses the powered HyAB distance into [0, 1]: the lower p_c of the
// range maps linearly to [0, p_t], the rest to [p_t, 1].
double remapColorError(double distance) {
    // In float, as the error map is kept: a double pow per pixel was most of the comparison.
    const double e = std::pow(static_cast<float>(distance), static_cast<float>(kQc)), cmax = maxColorError();
    const double r = e < kPc * cmax ? kPt / (kPc * cmax) * e : kPt + (e - kPc * cmax) / (cmax - kPc * cmax) * (1 - kPt);
    return std::clamp(r, 0.0, 1.0);
}

// out[x] += k * src[x] over a run of n pixels: the convolutions' inner
// loop, also compiled for AVX2 and chosen at load time where the CPU has it
// (no FMA either way: the same sums on any machine).
[[gnu::target_clones("avx2", "default")]] void addScaledRun(float* out, const float* src, float k, int n) {
    for (int x = 0; x < n; ++x) out[x] += k * src[x];
}

// 1-D correlation along a row, clamped to the edge. The interior adds one
// tap at a time over the whole run of pixels (contiguous, so it
// vectorises), in the same tap order as a per-pixel sum; the ends clamp.
void correlateRow(const float* row, int w, const std::vector<float>& k, float* out) {
    const int r = static_cast<int>(k.size() / 2);
    const int begin = std::min(r, w), end = std::max(begin, w - r);
    const auto clamped = [&](int x) {
        float s = 0;
        for (int j = -r; j <= r; ++j) s += k[j + r] * row[std::clamp(x + j, 0, w - 1)];
        out[x] = s;
    };
    for (int x = 0; x < begin; ++x) clamped(x);
    for (int x = end; x < w; ++x) clamped(x);
    std::fill(out + begin, out + end, 0.0f);
    for (std::size_t j = 0; j < k.size(); ++j) addScaledRun(out + begin, row + begin + j - r, k[j], end - begin);
}

// Rows are independent, so they run in parallel and the result does not
// depend on the thread count. Along columns, whole rows are scaled and
// added (contiguous, so it vectorises).
Plane convolve1d(const Plane& p, const Kernel& kernel, bool alongRows) {
    Plane out(p.w, p.h);
    const std::vector<float> k(kernel.begin(), kernel.end());
    const int r = static_cast<int>(k.size() / 2);
    tbb::parallel_for(0, p.h, [&](int y) {
        float* o = &out.v[static_cast<std::size_t>(y) * p.w];
        if (alongRows) return correlateRow(&p.v[static_cast<std::size_t>(y) * p.w], p.w, k, o);
        for (int j = -r; j <= r; ++j)
            addScaledRun(o, &p.v[static_cast<std::size_t>(std::clamp(y + j, 0, p.h - 1)) * p.w], k[j + r], p.w);
    });
    return out;
}

Plane convolve(const Plane& p, const Kernel& kx, const Kernel& ky) {
    return convolve1d(convolve1d(p, kx, true), ky, false);
}

// fn(i) for every pixel index, in parallel; each i is written by one call,
// so the result does not depend on the thread count.
template <class Fn>
void forPixels(std::size_t n, Fn&& fn) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) fn(i);
    });
}

// out += w * p
void addScaled(Plane& out, const Plane& p, double w) {
    forPixels(out.v.size(), [&](std::size_t i) { out.v[i] += static_cast<float>(w * p.v[i]); });
}

// One channel's contrast sensitivity as a sum of two Gaussians in visual
// angle: a_k sqrt(pi / b_k) exp(-pi^2 r^2 / b_k), r in degrees (the paper's constants).
struct Csf {
    double a1, b1, a2, b2;
};
constexpr std::array<Csf, 3> kCsf{{{1, 0.0047, 0, 1e-5}, {1, 0.0053, 0, 1e-5}, {34.1, 0.04, 13.5, 0.025}}};

Kernel csfTerm(double b, int radius, double ppd) {
    Kernel k(2 * radius + 1);
    for (int i = -radius; i <= radius; ++i) k[i + radius] = std::exp(-kPi * kPi * (i / ppd) * (i / ppd) / b);
    return k;
}

double sum(const Kernel& k) {
    double s = 0;
    for (double v : k) s += v;
    return s;
}

// The 2-D filter is separable per Gaussian term; the whole is normalised to
// sum 1, so flat regions keep their colour. Radius: 3 sigma of the widest term.
Plane csfFilter(const Plane& p, const Csf& c, double ppd) {
    const double bMax = c.a2 > 0 ? std::max(c.b1, c.b2) : c.b1;
    const int radius = static_cast<int>(std::ceil(3 * std::sqrt(bMax / (2 * kPi * kPi)) * ppd));
    std::vector<std::pair<double, Kernel>> terms{{c.a1 * std::sqrt(kPi / c.b1), csfTerm(c.b1, radius, ppd)}};
    if (c.a2 > 0) terms.push_back({c.a2 * std::sqrt(kPi / c.b2), csfTerm(c.b2, radius, ppd)});
    double total = 0;
    for (const auto& [w, k] : terms) total += w * sum(k) * sum(k);
    Plane out(p.w, p.h);
    for (const auto& [w, k] : terms) addScaled(out, convolve(p, k, k), w / total);
    return out;
}

// A display value: clamped to [0, 1], NaN shows as black.
double displayValue(float v) { return std::isnan(v) ? 0.0 : std::clamp(static_cast<double>(v), 0.0, 1.0); }

// R, G, B as displayed, as YCxCz planes.
std::array<Plane, 3> toYcxcz(const Image& img) {
    const int ch[3] = {img.channelIndex("R"), img.channelIndex("G"), img.channelIndex("B")};
    const Plane empty(img.width(), img.height());
    std::array<Plane, 3> out{empty, empty, empty};
    const int w = img.width();
    forPixels(empty.v.size(), [&](std::size_t p) {
        const int x = static_cast<int>(p % w), y = static_cast<int>(p / w);
        Vec3 rgb;
        for (int i = 0; i < 3; ++i) rgb[i] = displayValue(img.at(x, y, ch[i]));
        const Vec3 c = relXyzToYcxcz(rgbToRelXyz(rgb));
        for (int i = 0; i < 3; ++i) out[i].v[p] = static_cast<float>(c[i]);
    });
    return out;
}

// A CSF-filtered YCxCz image as Hunt-adjusted CIELAB, per pixel.
std::vector<Vec3> toHuntLab(const std::array<Plane, 3>& p) {
    std::vector<Vec3> out(p[0].v.size());
    forPixels(out.size(), [&](std::size_t i) {
        Vec3 rgb = relXyzToRgb(ycxczToRelXyz({p[0].v[i], p[1].v[i], p[2].v[i]}));
        for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
        out[i] = huntLab(rgb);
    });
    return out;
}

// Scales positive taps to sum 1 and negative taps to sum -1, so a response
// lies in [-1, 1] and a flat region gives 0.
void balance(Kernel& k) {
    double pos = 0, neg = 0;
    for (double v : k) (v > 0 ? pos : neg) += v;
    for (double& v : k) v = v > 0 ? v / pos : v < 0 ? v / -neg : 0;
}

// Gaussian (sum 1), its first derivative (edges) and second (points). The
// 2-D kernels are derivative x Gaussian, so balancing the 1-D derivative
// balances the 2-D kernel as the paper does (positive 1, negative -1).
struct FeatureKernels {
    Kernel gauss, edge, point;
};

FeatureKernels featureKernels(double ppd) {
    const double sd = 0.5 * kFeatureWidthDeg * ppd;
    const int radius = static_cast<int>(std::ceil(3 * sd));
    FeatureKernels f{Kernel(2 * radius + 1), Kernel(2 * radius + 1), Kernel(2 * radius + 1)};
    for (int i = -radius; i <= radius; ++i) {
        const double g = std::exp(-0.5 * i * i / (sd * sd));
        f.gauss[i + radius] = g, f.edge[i + radius] = -i * g, f.point[i + radius] = (i * i / (sd * sd) - 1) * g;
    }
    const double s = sum(f.gauss);
    for (double& v : f.gauss) v /= s;
    balance(f.edge), balance(f.point);
    return f;
}

// |(Gx * y, Gy * y)| per pixel for a derivative kernel d (Gaussian across it).
Plane featureMagnitude(const Plane& y, const Kernel& d, const Kernel& g) {
    Plane fx = convolve(y, d, g), fy = convolve(y, g, d);
    // Balanced kernels keep responses in [-1, 1]: the plain root cannot overflow.
    forPixels(fx.v.size(), [&](std::size_t i) { fx.v[i] = std::sqrt(fx.v[i] * fx.v[i] + fy.v[i] * fy.v[i]); });
    return fx;
}

// Achromatic channel in [0, 1] (relative luminance) from YCxCz's Y.
Plane achromatic(const Plane& ycxczY) {
    Plane out = ycxczY;
    for (float& v : out.v) v = (v + 16) / 116;
    return out;
}

std::string sizeText(const Image& img) { return std::to_string(img.width()) + "x" + std::to_string(img.height()); }

void checkInputs(const Image& img, double ppd, const char* role) {
    for (const char* c : {"R", "G", "B"})
        if (img.channelIndex(c) < 0) throw Error(std::string("FLIP: the ") + role + " image has no " + c + " channel");
    if (!(ppd > 0) || !std::isfinite(ppd))
        throw Error("FLIP: pixels per degree must be a positive number, not " + std::to_string(ppd));
}

// What the comparison needs of one image: its CSF-filtered colour as
// CIELAB, and the edge and point magnitudes of its achromatic channel.
struct FlipSide {
    std::vector<Vec3> lab;
    Plane edges, points;
};

FlipSide prepareSide(const Image& img, double ppd) {
    const std::array<Plane, 3> c = toYcxcz(img);
    const std::array<Plane, 3> filtered{csfFilter(c[0], kCsf[0], ppd), csfFilter(c[1], kCsf[1], ppd), csfFilter(c[2], kCsf[2], ppd)};
    const FeatureKernels k = featureKernels(ppd);
    const Plane y = achromatic(c[0]);
    return {toHuntLab(filtered), featureMagnitude(y, k.edge, k.gauss), featureMagnitude(y, k.point, k.gauss)};
}

}  // namespace

struct FlipReference::Side : FlipSide {};

FlipReference::FlipReference(const Image& reference, double pixelsPerDegree)
    : width_(reference.width()), height_(reference.height()), ppd_(pixelsPerDegree) {
    checkInputs(reference, pixelsPerDegree, "reference");
    side_ = std::make_unique<const Side>(Side{prepareSide(reference, pixelsPerDegree)});
}

FlipReference::~FlipReference() = default;

// dE = dEc^(1 - dEf) per pixel, dEc the remapped HyAB distance, dEf =
// (max(|edge difference|, |point difference|) / sqrt 2)^q_f, into map when
// one is given. The mean sums each row, then the rows in order: the same on
// any thread count.
double FlipReference::compareInto(const Image& test, float* map) const {
    if (test.width() != width_ || test.height() != height_)
        throw Error("FLIP: images differ in size: " + sizeText(test) + " vs " + std::to_string(width_) + "x" + std::to_string(height_));
    checkInputs(test, ppd_, "test");
    const FlipSide t = prepareSide(test, ppd_);
    const FlipSide& r = *side_;
    std::vector<double> rowSums(height_, 0.0);
    tbb::parallel_for(0, height_, [&](int y) {
        for (std::size_t i = std::size_t(y) * width_, end = i + width_; i < end; ++i) {
            const double ec = static_cast<float>(remapColorError(hyab(t.lab[i], r.lab[i])));
            const double d = std::max(std::abs(t.edges.v[i] - r.edges.v[i]), std::abs(t.points.v[i] - r.points.v[i])) / std::numbers::sqrt2;
            const double ef = static_cast<float>(std::sqrt(std::min(d, 1.0)));  // q_f = 1/2
            const float e = std::pow(static_cast<float>(ec), static_cast<float>(1.0 - ef));  // float, as the map is
            if (map) map[i] = e;
            rowSums[y] += e;
        }
    });
    double total = 0;
    for (double s : rowSums) total += s;
    return width_ * height_ == 0 ? 0 : total / (double(width_) * height_);
}

FlipResult FlipReference::compare(const Image& test) const {
    FlipResult result{0, Image(width_, height_, {"FLIP"})};
    result.mean = compareInto(test, result.errorMap.data().data());
    return result;
}

double FlipReference::meanError(const Image& test) const { return compareInto(test, nullptr); }

FlipResult flipError(const Image& test, const Image& reference, double pixelsPerDegree) {
    if (test.width() != reference.width() || test.height() != reference.height())
        throw Error("FLIP: images differ in size: " + sizeText(test) + " vs " + sizeText(reference));
    checkInputs(test, pixelsPerDegree, "test");
    return FlipReference(reference, pixelsPerDegree).compare(test);
}

}  // namespace weft
