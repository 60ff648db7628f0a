#include "core/volume/optics/preintegration.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "core/base/error.hpp"

namespace weft {

namespace {

constexpr int kGaussOrder = 8;
// Quadrature sub-intervals span equal-ish optical depth, not equal length,
// so a dense piece is resolved where its transmittance still matters. The
// first spans depth 2; later ones grow by half the depth already crossed,
// since their error is scaled by the transmittance reaching them. With 8
// Gauss-Legendre nodes the mean transmittance is then accurate to ~1e-10
// with at most 6 sub-intervals per piece.
constexpr double kDepthStep = 2.0;
constexpr double kDepthGrowth = 0.5;
// Beyond this optical depth inside a piece transmittance is below 5e-18:
// the rest of the piece is integrated as fully opaque.
constexpr double kDepthCut = 40.0;
// Once the light reaching a piece is this small its colour cannot matter.
constexpr double kNegligibleTransmittance = 1e-20;
// Extinction above this is as opaque as any larger value and keeps products finite.
constexpr double kMaxExtinction = 1e100;
constexpr int kMaxResolution = 4096;

struct GaussRule {
    std::array<double, kGaussOrder> node{}, weight{};  // on [-1, 1]
};

// Legendre polynomial P_n(x) and its derivative, by the three-term recurrence.
std::pair<double, double> legendre(int n, double x) {
    double p0 = 1, p1 = x;
    for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1, p1 = p2;
    }
    return {p1, n * (x * p1 - p0) / (x * x - 1)};
}

// Nodes and weights found once by Newton's method on P_n.
const GaussRule& gaussRule() {
    static const GaussRule rule = [] {
        GaussRule r;
        for (int i = 0; i < kGaussOrder; ++i) {
            double x = std::cos(std::numbers::pi * (i + 0.75) / (kGaussOrder + 0.5));
            for (int iter = 0; iter < 100; ++iter) {
                const auto [p, dp] = legendre(kGaussOrder, x);
                const double dx = p / dp;
                x -= dx;
                if (std::abs(dx) < 1e-16) break;
            }
            const double dp = legendre(kGaussOrder, x).second;
            r.node[i] = x;
            r.weight[i] = 2 / ((1 - x * x) * dp * dp);
        }
        return r;
    }();
    return rule;
}

double cleanExtinction(double tau) {
    return tau > 0 ? std::min(tau, kMaxExtinction) : 0.0;  // also maps NaN to 0
}

double cleanS(double s) {
    return s > 0 ? std::min(s, 1.0) : 0.0;  // also maps NaN to 0
}

// One interval of s on which the transfer function is linear.
struct TfPiece {
    double s0 = 0, s1 = 0;
    TfPoint v0, v1;  // values at s0 and s1 (limits from inside the interval)

    TfPoint at(double s) const {
        const double t = s1 > s0 ? (s - s0) / (s1 - s0) : 0.0;
        TfPoint p;
        p.s = s;
        for (int c = 0; c < 3; ++c) p.color[c] = v0.color[c] + t * (v1.color[c] - v0.color[c]);
        p.extinction = cleanExtinction(v0.extinction + t * (v1.extinction - v0.extinction));
        return p;
    }
};

// The pieces of [0, 1], in increasing s. Constant beyond the end points as
// TransferFunction::atS is; a step (two points at one s) is a piece boundary.
std::vector<TfPiece> tfPieces(const TransferFunction& tf) {
    const std::vector<TfPoint>& pts = tf.points();
    if (pts.empty()) throw Error("pre-integration: transfer function has no points");
    std::vector<TfPiece> pieces;
    auto addPiece = [&](double s0, double s1, const TfPoint& a, const TfPoint& b) {
        const TfPiece whole{s0, s1, a, b};
        const double lo = std::max(s0, 0.0), hi = std::min(s1, 1.0);
        if (hi > lo) pieces.push_back({lo, hi, whole.at(lo), whole.at(hi)});
    };
    addPiece(0.0, pts.front().s, pts.front(), pts.front());
    for (size_t i = 0; i + 1 < pts.size(); ++i) addPiece(pts[i].s, pts[i + 1].s, pts[i], pts[i + 1]);
    addPiece(pts.back().s, 1.0, pts.back(), pts.back());
    if (pieces.empty()) addPiece(0.0, 1.0, pts.front(), pts.front());  // all points outside [0, 1]
    return pieces;
}

// u in [0, 1] where a u + b u^2 reaches depth (the root that is monotone in
// depth), written to avoid cancellation and overflow.
double depthRoot(double a, double b, double depth) {
    double root;
    if (b >= 0) {
        root = std::hypot(a, 2 * std::sqrt(b * depth));
    } else {
        const double q = 2 * std::sqrt(-b * depth);
        root = std::sqrt(std::max(0.0, (a - q) * (a + q)));
    }
    const double denom = a + root;
    return denom > 0 ? std::clamp(2 * depth / denom, 0.0, 1.0) : 1.0;
}

// A piece of length h where extinction goes linearly from tau0 to tau1. Its
// colour, for colour going linearly from c0 to c1, is c0 * w0 + c1 * w1:
// integrating by parts, w0 = 1 - M and w1 = M - exp(-depth) with
// M = int_0^1 exp(-(a u + b u^2)) du the mean transmittance inside the piece.
// Both weights are >= 0 and sum to the piece's opacity.
struct PieceWeights {
    double depth = 0, w0 = 0, w1 = 0;
};

// Gauss-Legendre nodes over [0, uEnd] of a piece whose optical depth is
// D(u) = a u + b u^2 (total `depth`), on sub-intervals of equal-ish depth:
// node(u, weight, expm1(-D(u))) for each. Returns uEnd: 1, or where the
// depth reaches kDepthCut (beyond it the piece is opaque).
template <class Node>
double depthQuadrature(double a, double b, double depth, Node&& node) {
    const double depthEnd = std::min(depth, kDepthCut);
    const GaussRule& rule = gaussRule();
    double uLo = 0, depthLo = 0;
    for (bool last = false; !last;) {
        const double depthHi = std::min(depthEnd, depthLo + kDepthStep + kDepthGrowth * depthLo);
        last = depthHi >= depthEnd;
        const double uHi = last && depthEnd == depth ? 1.0 : depthRoot(a, b, depthHi);
        const double half = 0.5 * (uHi - uLo), mid = 0.5 * (uHi + uLo);
        for (int i = 0; i < kGaussOrder; ++i) {
            const double u = mid + half * rule.node[i];
            node(u, half * rule.weight[i], std::expm1(-u * (a + b * u)));
        }
        uLo = uHi, depthLo = depthHi;
    }
    return uLo;
}

PieceWeights pieceWeights(double tau0, double tau1, double h) {
    PieceWeights out;
    out.depth = 0.5 * (tau0 + tau1) * h;
    if (!(out.depth > 0)) return out;
    if (!std::isfinite(out.depth)) {  // opaque at its front: extinction x length overflows
        out.w0 = 1;
        return out;
    }
    double mean = 0, opaque = 0;  // integrals of exp(-D(u)) and 1 - exp(-D(u)) over [0, 1]
    const double uEnd = depthQuadrature(tau0 * h, 0.5 * (tau1 - tau0) * h, out.depth, [&](double, double w, double em) {
        mean += w * (1 + em);
        opaque -= w * em;
    });
    opaque += 1 - uEnd;  // past the depth cut the piece is opaque
    const double alpha = -std::expm1(-out.depth);
    out.w0 = std::clamp(opaque, 0.0, alpha);
    // For thin pieces alpha - (1 - M) keeps relative precision; for thick ones M - exp(-depth) does.
    const double w1 = out.depth < 1 ? alpha - opaque : mean - std::exp(-out.depth);
    out.w1 = std::clamp(w1, 0.0, alpha - out.w0);
    return out;
}

// The emission weights of a piece from x0 to x0 + h of a segment of length
// L, divided by L (f0 = x0 / L, fh = h / L), for the light reaching it
// unattenuated: int (1 - x/L) exp(-D) dx / L and int (x/L) exp(-D) dx / L.
struct EmissionMoments {
    double front = 0, back = 0;
};

EmissionMoments pieceEmission(double tau0, double tau1, double h, double f0, double fh) {
    const double depth = 0.5 * (tau0 + tau1) * h;
    if (!(depth > 0)) return {fh * (1 - f0 - 0.5 * fh), fh * (f0 + 0.5 * fh)};  // transparent: the ramp's area
    if (!std::isfinite(depth)) return {};  // opaque within a vanishing part of the piece (extinction x length overflows)
    EmissionMoments m;
    depthQuadrature(tau0 * h, 0.5 * (tau1 - tau0) * h, depth, [&](double u, double w, double em) {
        const double t = w * (1 + em), back = f0 + u * fh;
        m.front += t * std::max(0.0, 1 - back), m.back += t * back;
    });
    return {m.front * fh, m.back * fh};
}

// The emission moments of a segment of constant extinction, depth d = tau L,
// divided by L: int_0^1 (1 - u) exp(-d u) du and int_0^1 u exp(-d u) du.
// Series where the closed forms cancel (error < 1e-10), their limits where
// d^2 would overflow.
EmissionMoments constantEmission(double d) {
    if (d < 1e-2) return {0.5 - d / 6 + d * d / 24 - d * d * d / 120, 0.5 - d / 3 + d * d / 8 - d * d * d / 30};
    if (d > 1e6) return {(1 - 1 / d) / d, 1 / d / d};
    const double e = std::exp(-d);
    return {(d + std::expm1(-d)) / (d * d), (-std::expm1(-d) - d * e) / (d * d)};
}

// Walks a segment through the transfer function pieces, front to back.
class SegmentIntegrator {
public:
    explicit SegmentIntegrator(const TransferFunction& tf) : tf_(tf), pieces_(tfPieces(tf)) {}

    PreintSample integrate(double sFront, double sBack, double length) const {
        sFront = cleanS(sFront), sBack = cleanS(sBack);
        if (!(length > 0)) return {0, 0, 0, 0};
        if (sFront == sBack) return constantSegment(sFront, length);
        std::array<double, 3> color{0, 0, 0};
        const double depth = walk(sFront, sBack, length, [&](const TfPoint& in, const TfPoint& out, double, double h, double transmittance) {
            const PieceWeights w = pieceWeights(in.extinction, out.extinction, h);
            for (int c = 0; c < 3; ++c) color[c] += transmittance * (w.w0 * in.color[c] + w.w1 * out.color[c]);
            return w.depth;
        });
        const double alpha = -std::expm1(-depth);
        return {float(color[0]), float(color[1]), float(color[2]), float(alpha)};
    }

    // The emission weights divided by the length (table entries).
    EmissionMoments emission(double sFront, double sBack, double length) const {
        sFront = cleanS(sFront), sBack = cleanS(sBack);
        if (!(length > 0)) return {0.5, 0.5};
        if (sFront == sBack) return constantEmission(cleanExtinction(tf_.atS(sFront).extinction) * length);
        EmissionMoments m;
        walk(sFront, sBack, length, [&](const TfPoint& in, const TfPoint& out, double x0, double h, double transmittance) {
            const EmissionMoments piece = pieceEmission(in.extinction, out.extinction, h, x0 / length, h / length);
            m.front += transmittance * piece.front, m.back += transmittance * piece.back;
            return 0.5 * (in.extinction + out.extinction) * h;
        });
        return m;
    }

private:
    // Closed form, the same as RayAccumulator::add(c, segmentOpacity(tau, L)).
    PreintSample constantSegment(double s, double length) const {
        const TfPoint p = tf_.atS(s);
        const double alpha = -std::expm1(-cleanExtinction(p.extinction) * length);
        return {float(p.color[0] * alpha), float(p.color[1] * alpha), float(p.color[2] * alpha), float(alpha)};
    }

    // piece(in, out, x0, h, transmittance) for each piece of the segment the
    // light still reaches, returning its optical depth; the segment's depth.
    template <class Piece>
    double walk(double sFront, double sBack, double length, Piece&& piece) const {
        return sFront < sBack ? walkIn<true>(sFront, sBack, length, piece) : walkIn<false>(sFront, sBack, length, piece);
    }
    template <bool Increasing, class Piece>
    double walkIn(double sFront, double sBack, double length, Piece& piece) const;

    const TransferFunction& tf_;
    std::vector<TfPiece> pieces_;
};

template <bool Increasing, class Piece>
double SegmentIntegrator::walkIn(double sFront, double sBack, double length, Piece& piece) const {
    const double lo = std::min(sFront, sBack), hi = std::max(sFront, sBack), span = hi - lo;
    double depth = 0, xPrev = 0;
    const int n = int(pieces_.size());
    for (int k = 0; k < n; ++k) {
        const TfPiece& p = pieces_[Increasing ? k : n - 1 - k];
        const double a = std::max(p.s0, lo), b = std::min(p.s1, hi);
        if (!(b > a)) continue;
        const double sIn = Increasing ? a : b, sOut = Increasing ? b : a;
        // Distance along the segment where it leaves this piece; exactly L at the back.
        const double x = sOut == sBack ? length : length * (std::abs(sOut - sFront) / span);
        const TfPoint in = p.at(sIn), out = p.at(sOut);
        const double transmittance = std::exp(-depth);
        if (transmittance < kNegligibleTransmittance) depth += 0.5 * (in.extinction + out.extinction) * (x - xPrev);
        else depth += piece(in, out, xPrev, x - xPrev, transmittance);
        xPrev = x;
    }
    return depth;
}

float quantize8(float v) {
    return std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f;
}

// Table coordinate of s: clamped to [0, res - 1], NaN read as 0.
float gridCoord(float s, int resolution) {
    const float x = s * float(resolution - 1);
    if (!(x > 0.0f)) return 0.0f;
    return std::min(x, float(resolution - 1));
}

// The table coordinate below which clear() holds. Entry e integrates
// between s = e / (resolution - 1) values; a cell with x < K reads entries
// up to K, and those lie strictly below the first extinction.
float clearEntriesOf(const TransferFunction& tf, int resolution) {
    const double below = tf.zeroExtinctionBelow();
    if (below == std::numeric_limits<double>::infinity()) return std::numeric_limits<float>::infinity();
    const double toS = 1.0 / (resolution - 1);
    int last = -1;
    while (last + 1 < resolution && (last + 1) * toS < below) ++last;
    return last >= 1 ? float(last) : -std::numeric_limits<float>::infinity();
}

}  // namespace

PreintSample PreintegrationTable::integrateSegment(const TransferFunction& tf, double sFront, double sBack,
                                                   double length) {
    if (!(length >= 0)) throw Error("pre-integration: segment length must be >= 0, got " + std::to_string(length));
    return SegmentIntegrator(tf).integrate(sFront, sBack, length);
}

EmissionWeights PreintegrationTable::integrateEmission(const TransferFunction& tf, double sFront, double sBack, double length) {
    if (!(length >= 0)) throw Error("pre-integration: segment length must be >= 0, got " + std::to_string(length));
    const EmissionMoments m = SegmentIntegrator(tf).emission(sFront, sBack, length);
    // Saturate rather than overflow: a clear segment longer than 3e38 voxels
    // would weigh more than a float holds.
    const auto weight = [length](double moment) { return float(std::min(moment * length, double(std::numeric_limits<float>::max()))); };
    return {weight(m.front), weight(m.back)};
}

struct PreintegrationTable::Integrator {
    explicit Integrator(const TransferFunction& f) : tf(f), segment(tf) {}
    TransferFunction tf;  // a copy: blocks are built after the caller's may be gone
    SegmentIntegrator segment;
};

PreintegrationTable::PreintegrationTable(const TransferFunction& tf, std::vector<double> lengths, int resolution,
                                         PreintPrecision precision, bool withEmission)
    : lengths_(std::move(lengths)), resolution_(resolution), precision_(precision) {
    if (lengths_.empty()) throw Error("pre-integration table: needs at least one segment length");
    for (double l : lengths_)
        if (!(l > 0) || !std::isfinite(l))
            throw Error("pre-integration table: segment lengths must be positive and finite, got " +
                        std::to_string(l));
    if (resolution_ < 2 || resolution_ > kMaxResolution)
        throw Error("pre-integration table: resolution must be in [2, " + std::to_string(kMaxResolution) +
                    "], got " + std::to_string(resolution_));
    integrator_ = std::make_unique<Integrator>(tf);
    clearEntries_ = clearEntriesOf(tf, resolution_);
    blocksPerAxis_ = std::size_t((resolution_ + kPreintBlock - 1) / kPreintBlock);
    blockState_ = std::make_unique<std::atomic<std::uint8_t>[]>(blockCount());
    for (std::size_t b = 0; b < blockCount(); ++b) blockState_[b].store(kEmpty, std::memory_order_relaxed);
    table_.resize(lengths_.size() * size_t(resolution_) * size_t(resolution_));
    if (withEmission) emission_.resize(table_.size());
}

PreintegrationTable::~PreintegrationTable() = default;

PreintegrationTable::BlockRange PreintegrationTable::rangeOf(std::size_t block) const {
    const std::size_t perLength = blocksPerAxis_ * blocksPerAxis_;
    const int front0 = int(block % perLength / blocksPerAxis_) * kPreintBlock, back0 = int(block % blocksPerAxis_) * kPreintBlock;
    return {int(block / perLength), front0, std::min(resolution_, front0 + kPreintBlock), back0,
            std::min(resolution_, back0 + kPreintBlock)};
}

// One block's entries; the first thread to need it builds it, others wait.
void PreintegrationTable::buildBlock(std::size_t block) const {
    std::atomic<std::uint8_t>& state = blockState_[block];
    std::uint8_t expected = kEmpty;
    if (!state.compare_exchange_strong(expected, kBuilding, std::memory_order_acquire)) {
        for (std::uint8_t now = expected; now != kBuilt; now = state.load(std::memory_order_acquire)) state.wait(now, std::memory_order_acquire);
        return;
    }
    const BlockRange r = rangeOf(block);
    const double toS = 1.0 / (resolution_ - 1), length = lengths_[std::size_t(r.length)];
    const SegmentIntegrator& in = integrator_->segment;
    for (int front = r.front0; front < r.front1; ++front)
        for (int back = r.back0; back < r.back1; ++back) {
            const std::size_t at = (std::size_t(r.length) * resolution_ + std::size_t(front)) * resolution_ + std::size_t(back);
            PreintSample e = in.integrate(front * toS, back * toS, length);
            if (precision_ == PreintPrecision::Bits8) e = {quantize8(e.r), quantize8(e.g), quantize8(e.b), quantize8(e.a)};
            table_[at] = e;
            if (emission_.empty()) continue;
            const EmissionMoments m = in.emission(front * toS, back * toS, length);
            EmissionWeights w{float(m.front), float(m.back)};  // both in [0, 1]: the same 8-bit emulation applies
            if (precision_ == PreintPrecision::Bits8) w = {quantize8(w.front), quantize8(w.back)};
            emission_[at] = w;
        }
    state.store(kBuilt, std::memory_order_release);
    state.notify_all();
}

void PreintegrationTable::buildAll() const {
    tbb::parallel_for(std::size_t(0), blockCount(), [&](std::size_t b) {
        if (blockState_[b].load(std::memory_order_acquire) != kBuilt) buildBlock(b);
    });
    complete_.store(true, std::memory_order_release);
}

std::int64_t PreintegrationTable::entriesBuilt() const {
    std::int64_t n = 0;
    for (std::size_t b = 0; b < blockCount(); ++b) {
        if (blockState_[b].load(std::memory_order_acquire) != kBuilt) continue;
        const BlockRange r = rangeOf(b);
        n += std::int64_t(r.front1 - r.front0) * (r.back1 - r.back0);
    }
    return n;
}

double PreintegrationTable::length(int index) const {
    if (index < 0 || index >= lengthCount())
        throw Error("pre-integration table: length index " + std::to_string(index) + " out of range");
    return lengths_[index];
}

namespace {

// The four table entries around (sFront, sBack) and their bilinear weights.
struct Bilinear {
    int front, back;  // the cell's first entry
    std::size_t i00, i01, i10, i11;
    float tx, ty;
    // (1 - t) a + t b returns an entry exactly at t = 0 and t = 1.
    float mix(float v00, float v01, float v10, float v11) const {
        const float front0 = (1 - ty) * v00 + ty * v01, front1 = (1 - ty) * v10 + ty * v11;
        return (1 - tx) * front0 + tx * front1;
    }
};

Bilinear bilinear(int lengthIndex, int lengthCount, int resolution, float sFront, float sBack) {
    if (lengthIndex < 0 || lengthIndex >= lengthCount)
        throw Error("pre-integration table: length index " + std::to_string(lengthIndex) + " out of range");
    const float x = gridCoord(sFront, resolution), y = gridCoord(sBack, resolution);
    const int i = std::min(int(x), resolution - 2), j = std::min(int(y), resolution - 2);
    const std::size_t base = (std::size_t(lengthIndex) * resolution + i) * resolution + j;
    return {i, j, base, base + 1, base + resolution, base + resolution + 1, x - float(i), y - float(j)};
}

PreintSample mixed(const FreshBuffer<PreintSample>& table, const Bilinear& b) {
    const PreintSample &e00 = table[b.i00], &e01 = table[b.i01], &e10 = table[b.i10], &e11 = table[b.i11];
    return {b.mix(e00.r, e01.r, e10.r, e11.r), b.mix(e00.g, e01.g, e10.g, e11.g), b.mix(e00.b, e01.b, e10.b, e11.b),
            b.mix(e00.a, e01.a, e10.a, e11.a)};
}

}  // namespace

PreintSample PreintegrationTable::read(int lengthIndex, float sFront, float sBack) const {
    const Bilinear b = bilinear(lengthIndex, lengthCount(), resolution_, sFront, sBack);
    needCell(lengthIndex, b.front, b.back);
    return mixed(table_, b);
}

PreintSample PreintegrationTable::readComplete(int lengthIndex, float sFront, float sBack) const {
    if (!complete_.load(std::memory_order_relaxed)) return read(lengthIndex, sFront, sBack);  // not built whole after all
    return mixed(table_, bilinear(lengthIndex, lengthCount(), resolution_, sFront, sBack));
}

EmissionWeights PreintegrationTable::lookupEmission(int lengthIndex, float sFront, float sBack) const {
    if (emission_.empty()) throw Error("internal: pre-integration table built without emission");
    const Bilinear b = bilinear(lengthIndex, lengthCount(), resolution_, sFront, sBack);
    needCell(lengthIndex, b.front, b.back);
    const EmissionWeights &e00 = emission_[b.i00], &e01 = emission_[b.i01], &e10 = emission_[b.i10], &e11 = emission_[b.i11];
    const float length = float(lengths_[lengthIndex]);
    return {b.mix(e00.front, e01.front, e10.front, e11.front) * length, b.mix(e00.back, e01.back, e10.back, e11.back) * length};
}

}  // namespace weft
