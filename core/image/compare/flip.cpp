#include "core/image/compare/flip.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/base/error.hpp"
#include "core/base/memory/large_buffer.hpp"
#include "core/base/target_clones.hpp"

namespace weft {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95;  // q_f = 0.5 is a square root
constexpr double kFeatureWidthDeg = 0.082;  // w: sigma = w/2 degrees

// One channel of an image, row-major; uninitialised, as every pass writes
// its planes whole (in parallel, so their pages are first touched on every thread).
struct Plane {
    int w = 0, h = 0;
    FreshBuffer<float> v;
    Plane(int width, int height) : w(width), h(height), v(static_cast<std::size_t>(width) * height) {}
};

using Kernel = std::vector<double>;  // odd length, centred on the middle tap
using Vec3 = std::array<double, 3>;
using Mat3 = std::array<Vec3, 3>;
using Lab = std::array<float, 3>;  // Hunt-adjusted CIELAB

// Linear sRGB (Rec.709 primaries, D65) to CIE XYZ, and back.
constexpr Mat3 kRgbToXyz{{{0.4124564, 0.3575761, 0.1804375},
                          {0.2126729, 0.7151522, 0.0721750},
                          {0.0193339, 0.1191920, 0.9503041}}};
constexpr Mat3 kXyzToRgb{{{3.2404542, -1.5371385, -0.4985314},
                          {-0.9692660, 1.8760108, 0.0415560},
                          {0.0556434, -0.2040259, 1.0572252}}};

Mat3 mul(const Mat3& a, const Mat3& b) {
    Mat3 r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
    return r;
}

Vec3 mul(const Mat3& m, const Vec3& v) {
    Vec3 r{};
    for (int i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    return r;
}

Mat3 diagonal(const Vec3& d) { return {{{d[0], 0, 0}, {0, d[1], 0}, {0, 0, d[2]}}}; }

// The XYZ of RGB 1, 1, 1: XYZ is taken relative to it.
Vec3 whiteXyz() {
    Vec3 w{};
    for (int i = 0; i < 3; ++i) w[i] = kRgbToXyz[i][0] + kRgbToXyz[i][1] + kRgbToXyz[i][2];
    return w;
}

// out = m in + offset, in float: the colour conversions per pixel. Each is
// a product of the paper's linear steps, formed once in double.
struct Affine3 {
    std::array<std::array<float, 3>, 3> m{};
    std::array<float, 3> offset{};
    Affine3(const Mat3& mat, const Vec3& off) {
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) m[i][j] = static_cast<float>(mat[i][j]);
            offset[i] = static_cast<float>(off[i]);
        }
    }
    std::array<float, 3> operator()(float a, float b, float c) const {
        return {m[0][0] * a + m[0][1] * b + m[0][2] * c + offset[0], m[1][0] * a + m[1][1] * b + m[1][2] * c + offset[1],
                m[2][0] * a + m[2][1] * b + m[2][2] * c + offset[2]};
    }
};

// YCxCz (CIELAB without the cube root, so it is linear and may be
// filtered) from relative XYZ: (116 Y - 16, 500 (X - Y), 200 (Y - Z)).
constexpr Mat3 kRelXyzToYcxcz{{{0, 116, 0}, {500, -500, 0}, {0, 200, -200}}};
constexpr Mat3 kYcxczToRelXyz{{{1.0 / 116, 1.0 / 500, 0}, {1.0 / 116, 0, 0}, {1.0 / 116, 0, -1.0 / 200}}};
constexpr Vec3 kYcxczToRelXyzOffset{16.0 / 116, 16.0 / 116, 16.0 / 116};

const Affine3& rgbToRelXyz() {
    static const Vec3 w = whiteXyz();
    static const Affine3 a(mul(diagonal({1 / w[0], 1 / w[1], 1 / w[2]}), kRgbToXyz), {0, 0, 0});
    return a;
}

const Affine3& rgbToYcxcz() {
    static const Vec3 w = whiteXyz();
    static const Affine3 a(mul(kRelXyzToYcxcz, mul(diagonal({1 / w[0], 1 / w[1], 1 / w[2]}), kRgbToXyz)), {-16, 0, 0});
    return a;
}

const Affine3& ycxczToRgb() {
    static const Vec3 w = whiteXyz();
    static const Mat3 toRgb = mul(kXyzToRgb, diagonal(w));
    static const Affine3 a(mul(toRgb, kYcxczToRelXyz), mul(toRgb, kYcxczToRelXyzOffset));
    return a;
}

// Float stand-ins for cbrt and pow, inline so that the per-pixel loops
// vectorise (the library's are a call per pixel, most of a comparison).
// The cube root: fdlibm's first guess from the exponent bits, then two
// Halley steps (cubic convergence: a 3% guess ends within float rounding).
inline float cubeRoot(float x) {  // x > 0
    const auto halley = [x](float y) {
        const float y3 = y * y * y;
        return y * (y3 + 2 * x) / (2 * y3 + x);
    };
    return halley(halley(std::bit_cast<float>(std::bit_cast<std::uint32_t>(x) / 3 + 709958130u)));
}

// log2 of a normal x > 0: the exponent, and ln m of the mantissa m in
// [sqrt 1/2, sqrt 2) as 2 atanh((m - 1) / (m + 1)), whose series' first five
// terms leave an error below 1e-9.
inline float log2Of(float x) {
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
    float m = std::bit_cast<float>((bits & 0x007fffffu) | 0x3f800000u);
    const bool high = m > 1.41421356f;
    m = high ? 0.5f * m : m;
    const float e = float(int(bits >> 23) - 127) + (high ? 1.0f : 0.0f);
    const float s = (m - 1) / (m + 1), s2 = s * s;
    const float ln = 2 * s * (1 + s2 * (1.0f / 3 + s2 * (1.0f / 5 + s2 * (1.0f / 7 + s2 * (1.0f / 9)))));
    return e + ln * 1.44269504f;
}

// 2^t for t in [-126, 127]: 2^round(t) from the exponent bits, times the
// Taylor series of e^(f ln 2), |f| <= 1/2, to its eighth term (error below 1e-8).
inline float exp2Of(float t) {
    constexpr float kRound = 12582912.0f;  // 1.5 2^23: adding it rounds to a whole number (|t| < 2^22)
    const float n = (t + kRound) - kRound, x = (t - n) * 0.693147181f;
    const float p = 1 + x * (1 + x * (0.5f + x * (1.0f / 6 + x * (1.0f / 24 + x * (1.0f / 120 + x * (1.0f / 720 + x * (1.0f / 5040)))))));
    return p * std::bit_cast<float>(std::uint32_t(int(n) + 127) << 23);
}

// Minimum, maximum and clamp by value: std::min and std::clamp return
// references, whose selects GCC does not turn into vector blends.
inline float smaller(float a, float b) { return b < a ? b : a; }
inline float larger(float a, float b) { return a < b ? b : a; }
inline float clamped(float v, float lo, float hi) { return smaller(larger(v, lo), hi); }

// x^y for x >= 0 and y >= 0 (0^0 = 1, as std::pow); x below the smallest
// normal float counts as 0.
inline float powOf(float x, float y) {
    constexpr float kMin = std::numeric_limits<float>::min();
    const float p = exp2Of(y * log2Of(larger(x, kMin)));  // selects, not branches: the loops vectorise
    return x >= kMin ? p : y == 0 ? 1.0f : 0.0f;
}

float labF(float t) {
    constexpr float d = 6.0f / 29.0f;
    const float root = cubeRoot(larger(t, d * d * d)), line = t / (3 * d * d) + 4.0f / 29.0f;  // both, then a select
    return t > d * d * d ? root : line;
}

// CIELAB with the Hunt adjustment (chroma scaled by L/100): dark colours
// differ less. Inline, for the loop that converts whole rows (labRow).
inline Lab huntLab(const Affine3& toRelXyz, float r, float g, float b) {
    const std::array<float, 3> x = toRelXyz(r, g, b);
    const float fx = labF(x[0]), fy = labF(x[1]), fz = labF(x[2]);
    const float L = 116 * fy - 16;
    return {L, 0.01f * L * 500 * (fx - fy), 0.01f * L * 200 * (fy - fz)};
}

// HyAB: city-block in lightness, Euclidean in chroma (large differences).
// Lab values of colours in [0, 1] are bounded (|a|, |b| < 500): the plain root cannot overflow, and is faster than hypot.
float hyab(float L1, float a1, float b1, float L2, float a2, float b2) {
    const float da = a1 - a2, db = b1 - b2;
    return std::abs(L1 - L2) + std::sqrt(da * da + db * db);
}

// The largest colour error, green vs blue, after the power q_c.
float maxColorError() {
    static const float cmax = [] {
        const Lab g = huntLab(rgbToRelXyz(), 0, 1, 0), b = huntLab(rgbToRelXyz(), 0, 0, 1);
        return powOf(hyab(g[0], g[1], g[2], b[0], b[1], b[2]), float(kQc));
    }();
    return cmax;
}

// Compresses the powered HyAB distance into [0, 1]: the lower p_c of the
// range maps linearly to [0, p_t], the rest to [p_t, 1].
inline float remapColorError(float distance, float cmax) {
    const float e = powOf(distance, float(kQc)), knee = float(kPc) * cmax;
    const float r = e < knee ? float(kPt) / knee * e : float(kPt) + (e - knee) / (cmax - knee) * float(1 - kPt);
    return clamped(r, 0.0f, 1.0f);
}

// out[x] += k * src[x] over a run of n pixels: the convolutions' inner
// loop, also compiled for AVX2 and chosen at load time where the CPU has it
// (no FMA either way: the same sums on any machine).
WEFT_TARGET_CLONES("avx2", "default") void addScaledRun(float* out, const float* src, float k, int n) {
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

std::vector<float> taps(const Kernel& kernel, double scale = 1) {
    std::vector<float> k(kernel.size());
    for (std::size_t i = 0; i < k.size(); ++i) k[i] = static_cast<float>(kernel[i] * scale);
    return k;
}

// Rows are independent, so they run in parallel and the result does not
// depend on the thread count.
Plane filterRows(const Plane& p, const std::vector<float>& k) {
    Plane out(p.w, p.h);
    tbb::parallel_for(0, p.h, [&](int y) {
        correlateRow(&p.v[static_cast<std::size_t>(y) * p.w], p.w, k, &out.v[static_cast<std::size_t>(y) * p.w]);
    });
    return out;
}

// p filtered along columns, into out (add: added to it): whole rows are
// scaled and added (contiguous, so it vectorises), one output row per task.
void filterColumnsInto(const Plane& p, const std::vector<float>& k, Plane& out, bool add) {
    const int r = static_cast<int>(k.size() / 2);
    tbb::parallel_for(0, p.h, [&](int y) {
        float* o = &out.v[static_cast<std::size_t>(y) * p.w];
        if (!add) std::fill(o, o + p.w, 0.0f);
        for (int j = -r; j <= r; ++j)
            addScaledRun(o, &p.v[static_cast<std::size_t>(std::clamp(y + j, 0, p.h - 1)) * p.w], k[j + r], p.w);
    });
}

Plane filterColumns(const Plane& p, const std::vector<float>& k) {
    Plane out(p.w, p.h);
    filterColumnsInto(p, k, out, false);
    return out;
}

// fn(i) for every pixel index, in parallel; each i is written by one call,
// so the result does not depend on the thread count.
template <class Fn>
void forPixels(std::size_t n, Fn&& fn) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) fn(i);
    });
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
// sum 1, so flat regions keep their colour. Radius: 3 sigma of the widest
// term. Each term's weight rides on its column taps, and the terms' column
// passes write into one plane, the first setting it and the rest adding.
Plane csfFilter(const Plane& p, const Csf& c, double ppd) {
    const double bMax = c.a2 > 0 ? std::max(c.b1, c.b2) : c.b1;
    const int radius = static_cast<int>(std::ceil(3 * std::sqrt(bMax / (2 * kPi * kPi)) * ppd));
    std::vector<std::pair<double, Kernel>> terms{{c.a1 * std::sqrt(kPi / c.b1), csfTerm(c.b1, radius, ppd)}};
    if (c.a2 > 0) terms.push_back({c.a2 * std::sqrt(kPi / c.b2), csfTerm(c.b2, radius, ppd)});
    double total = 0;
    for (const auto& [w, k] : terms) total += w * sum(k) * sum(k);
    Plane out(p.w, p.h);
    for (std::size_t i = 0; i < terms.size(); ++i) {
        const auto& [w, k] = terms[i];
        filterColumnsInto(filterRows(p, taps(k)), taps(k, w / total), out, i > 0);
    }
    return out;
}

// A display value: clamped to [0, 1], NaN shows as black.
float displayValue(float v) { return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f); }

// R, G, B as displayed, as YCxCz planes, and the achromatic channel in
// [0, 1] (relative luminance, YCxCz's Y rescaled) for the features.
struct DisplayPlanes {
    std::array<Plane, 3> ycxcz;
    Plane achromatic;
};

DisplayPlanes toYcxcz(const Image& img) {
    const int ch[3] = {img.channelIndex("R"), img.channelIndex("G"), img.channelIndex("B")};
    const int w = img.width(), h = img.height(), n = img.channelCount();
    DisplayPlanes out{{Plane(w, h), Plane(w, h), Plane(w, h)}, Plane(w, h)};
    const Affine3& toYcxcz = rgbToYcxcz();
    tbb::parallel_for(0, h, [&](int y) {
        const float* px = img.pixel(0, y);
        for (std::size_t x = 0, i = std::size_t(y) * w; x < std::size_t(w); ++x, ++i, px += n) {
            const std::array<float, 3> c = toYcxcz(displayValue(px[ch[0]]), displayValue(px[ch[1]]), displayValue(px[ch[2]]));
            for (int k = 0; k < 3; ++k) out.ycxcz[k].v[i] = c[k];
            out.achromatic.v[i] = (c[0] + 16) / 116;
        }
    });
    return out;
}

// Hunt-adjusted CIELAB planes of n CSF-filtered YCxCz pixels. Both images'
// colours pass through this one loop, so the error is symmetric to the bit.
WEFT_TARGET_CLONES("avx2", "default") void labRow(const float* __restrict y, const float* __restrict cx,
                                                      const float* __restrict cz, std::size_t n, float* __restrict L,
                                                      float* __restrict a, float* __restrict b) {
    const Affine3 toRgb = ycxczToRgb(), toXyz = rgbToRelXyz();
    for (std::size_t i = 0; i < n; ++i) {
        const std::array<float, 3> rgb = toRgb(y[i], cx[i], cz[i]);
        const Lab lab = huntLab(toXyz, clamped(rgb[0], 0, 1), clamped(rgb[1], 0, 1), clamped(rgb[2], 0, 1));
        L[i] = lab[0], a[i] = lab[1], b[i] = lab[2];
    }
}

// Three planes of one image's colour as CIELAB.
struct LabPlanes {
    std::array<FreshBuffer<float>, 3> c;
    explicit LabPlanes(std::size_t n) : c{FreshBuffer<float>(n), FreshBuffer<float>(n), FreshBuffer<float>(n)} {}
    void fillRow(const std::array<Plane, 3>& filtered, std::size_t begin, std::size_t n) {
        labRow(&filtered[0].v[begin], &filtered[1].v[begin], &filtered[2].v[begin], n, &c[0][begin], &c[1][begin], &c[2][begin]);
    }
};

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
    std::vector<float> gauss, edge, point;
};

FeatureKernels featureKernels(double ppd) {
    const double sd = 0.5 * kFeatureWidthDeg * ppd;
    const int radius = static_cast<int>(std::ceil(3 * sd));
    Kernel gauss(2 * radius + 1), edge(2 * radius + 1), point(2 * radius + 1);
    for (int i = -radius; i <= radius; ++i) {
        const double g = std::exp(-0.5 * i * i / (sd * sd));
        gauss[i + radius] = g, edge[i + radius] = -i * g, point[i + radius] = (i * i / (sd * sd) - 1) * g;
    }
    balance(edge), balance(point);
    return {taps(gauss, 1 / sum(gauss)), taps(edge), taps(point)};
}

// |(Gx * y, Gy * y)| per pixel for a derivative kernel d, the Gaussian
// across it; gRows is y filtered along rows by the Gaussian, which the
// edges and the points share.
Plane featureMagnitude(const Plane& y, const Plane& gRows, const std::vector<float>& d, const std::vector<float>& g) {
    Plane fx = filterColumns(filterRows(y, d), g);
    const Plane fy = filterColumns(gRows, d);
    // Balanced kernels keep responses in [-1, 1]: the plain root cannot overflow.
    forPixels(fx.v.size(), [&](std::size_t i) { fx.v[i] = std::sqrt(fx.v[i] * fx.v[i] + fy.v[i] * fy.v[i]); });
    return fx;
}

std::string sizeText(const Image& img) { return std::to_string(img.width()) + "x" + std::to_string(img.height()); }

void checkInputs(const Image& img, double ppd, const char* role) {
    for (const char* c : {"R", "G", "B"})
        if (img.channelIndex(c) < 0) throw Error(std::string("FLIP: the ") + role + " image has no " + c + " channel");
    if (!(ppd > 0) || !std::isfinite(ppd))
        throw Error("FLIP: pixels per degree must be a positive number, not " + std::to_string(ppd));
}

// What the comparison needs of one image: its CSF-filtered colour (as
// YCxCz; CIELAB per pixel where it is compared), and the edge and point
// magnitudes of its achromatic channel.
struct FlipSide {
    std::array<Plane, 3> filtered;
    Plane edges, points;
};

FlipSide prepareSide(const Image& img, double ppd) {
    const DisplayPlanes c = toYcxcz(img);
    const FeatureKernels k = featureKernels(ppd);
    const Plane gRows = filterRows(c.achromatic, k.gauss);
    return {{csfFilter(c.ycxcz[0], kCsf[0], ppd), csfFilter(c.ycxcz[1], kCsf[1], ppd), csfFilter(c.ycxcz[2], kCsf[2], ppd)},
            featureMagnitude(c.achromatic, gRows, k.edge, k.gauss),
            featureMagnitude(c.achromatic, gRows, k.point, k.gauss)};
}

// The FLIP error of n pixels from both images' CIELAB planes and feature
// magnitudes: dE = dEc^(1 - dEf), dEc the remapped HyAB distance, dEf =
// (max(|edge difference|, |point difference|) / sqrt 2)^q_f.
struct ErrorRowInputs {
    const float *L[2], *a[2], *b[2], *edges[2], *points[2];
};

WEFT_TARGET_CLONES("avx2", "default") void errorRow(const ErrorRowInputs& in, std::size_t n, float cmax, float* out) {
    for (std::size_t i = 0; i < n; ++i) {
        const float ec = remapColorError(hyab(in.L[0][i], in.a[0][i], in.b[0][i], in.L[1][i], in.a[1][i], in.b[1][i]), cmax);
        const float d = larger(std::abs(in.edges[0][i] - in.edges[1][i]), std::abs(in.points[0][i] - in.points[1][i])) * 0.707106781f;
        const float ef = std::sqrt(smaller(d, 1.0f));  // q_f = 1/2
        out[i] = powOf(ec, 1 - ef);
    }
}

}  // namespace

// The reference keeps its colour as CIELAB, converted once.
struct FlipReference::Side {
    LabPlanes lab;
    Plane edges, points;
};

FlipReference::FlipReference(const Image& reference, double pixelsPerDegree)
    : width_(reference.width()), height_(reference.height()), ppd_(pixelsPerDegree) {
    checkInputs(reference, pixelsPerDegree, "reference");
    FlipSide s = prepareSide(reference, pixelsPerDegree);
    LabPlanes lab(s.edges.v.size());
    tbb::parallel_for(0, height_, [&](int y) { lab.fillRow(s.filtered, std::size_t(y) * width_, std::size_t(width_)); });
    side_ = std::make_unique<const Side>(Side{std::move(lab), std::move(s.edges), std::move(s.points)});
}

FlipReference::~FlipReference() = default;

// The error per pixel, into map when one is given. The mean sums each row,
// then the rows in order: the same on any thread count.
double FlipReference::compareInto(const Image& test, float* map) const {
    if (test.width() != width_ || test.height() != height_)
        throw Error("FLIP: images differ in size: " + sizeText(test) + " vs " + std::to_string(width_) + "x" + std::to_string(height_));
    checkInputs(test, ppd_, "test");
    const FlipSide t = prepareSide(test, ppd_);
    const Side& r = *side_;
    const std::size_t n = t.edges.v.size(), w = std::size_t(width_);
    LabPlanes lab(n);
    FreshBuffer<float> errors(map ? 0 : n);
    float* out = map ? map : errors.data();
    const float cmax = maxColorError();
    std::vector<double> rowSums(height_, 0.0);
    tbb::parallel_for(0, height_, [&](int y) {
        const std::size_t i = std::size_t(y) * w;
        lab.fillRow(t.filtered, i, w);
        const ErrorRowInputs in{{&lab.c[0][i], &r.lab.c[0][i]}, {&lab.c[1][i], &r.lab.c[1][i]}, {&lab.c[2][i], &r.lab.c[2][i]},
                                {&t.edges.v[i], &r.edges.v[i]}, {&t.points.v[i], &r.points.v[i]}};
        errorRow(in, w, cmax, out + i);
        double sum = 0;
        for (std::size_t k = 0; k < w; ++k) sum += out[i + k];
        rowSums[y] = sum;
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
