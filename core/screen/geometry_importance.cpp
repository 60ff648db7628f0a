// geometryImportance (core/screen/sample_budget.hpp): W_p of the normal and
// position range weights over a box window. The inner loop runs along a row
// for one window offset at a time, over plain float planes, with a
// polynomial exp, so the compiler vectorises it: 1024x768 with a 4x4 window
// is 12.6 million weights.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "core/base/error.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/screen/sample_budget.hpp"
#include "core/base/target_clones.hpp"

namespace weft {

namespace {

// e^-x for x >= +0 (NaN reads as "far": e^-80), relative error below 4e-7, exactly 1 at 0:
// 2^-t as 2^-floor(t) (exponent bits) times a degree-5 fit of 2^-f on [0, 1).
// The clamp compares the bits as unsigned integers (monotone for x >= +0;
// every NaN is above 80), which vectorises where a float compare does not.
inline float expNegative(float x) {
    constexpr std::uint32_t kLimit = std::bit_cast<std::uint32_t>(80.0f);
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
    x = std::bit_cast<float>(bits < kLimit ? bits : kLimit);
    const float t = x * 1.44269504f;
    const int i = int(t);
    const float f = t - float(i);
    const float p = 1.0f + f * (-0.693143443f + f * (0.240179254f + f * (-0.0552981325f + f * (0.00920975059f + f * -0.000947527541f))));
    return p * std::bit_cast<float>((127 - i) << 23);
}

struct Window {
    int lo, hi;  // offsets lo..hi along each axis
    explicit Window(int k) : lo(-(k / 2)), hi((k - 1) / 2) {}
    // Offsets d with 0 <= c + d < size.
    int inside(int c, int size) const { return std::min(hi, size - 1 - c) - std::max(lo, -c) + 1; }
};

struct Planes {
    const float* n[3];
    const float* p[3];
    float invN, invP;
};

// acc[x] += weight between (x, y) and (x + dx, y + dy) for every x with both inside.
template <bool UseN, bool UseP>
inline __attribute__((always_inline)) void accumulateOffset(const Planes& g, int width, int y, int dx, int dy, float* __restrict acc) {
    const int x0 = std::max(0, -dx), x1 = std::min(width, width - dx);
    const std::size_t a = std::size_t(y) * width + x0, b = std::size_t(y + dy) * width + std::size_t(x0 + dx);
    acc += x0;
    // An unused guide's planes are null, and an offset from null is undefined.
    const auto at = [](const float* plane, std::size_t i) { return plane ? plane + i : nullptr; };
    const float *n0 = at(g.n[0], a), *n1 = at(g.n[1], a), *n2 = at(g.n[2], a), *m0 = at(g.n[0], b), *m1 = at(g.n[1], b), *m2 = at(g.n[2], b);
    const float *p0 = at(g.p[0], a), *p1 = at(g.p[1], a), *p2 = at(g.p[2], a), *q0 = at(g.p[0], b), *q1 = at(g.p[1], b), *q2 = at(g.p[2], b);
    for (int x = 0; x < x1 - x0; ++x) {
        float e = 0;
        if constexpr (UseN) {
            const float u = n0[x] - m0[x], v = n1[x] - m1[x], w = n2[x] - m2[x];
            e += (u * u + v * v + w * w) * g.invN;
        }
        if constexpr (UseP) {
            const float u = p0[x] - q0[x], v = p1[x] - q1[x], w = p2[x] - q2[x];
            e += (u * u + v * v + w * w) * g.invP;
        }
        acc[x] += expNegative(e);
    }
}

// Cloned for AVX-512 and for AVX2 + FMA, picked at load time by what the CPU
// has. clang (14) cannot clone function templates: its builds (the sanitized
// one) take the default code path.
#if defined(__clang__)
#define WEFT_ROW_CLONES
#else
#define WEFT_ROW_CLONES WEFT_TARGET_CLONES("arch=x86-64-v4", "arch=x86-64-v3", "default")
#endif
template <bool UseN, bool UseP>
WEFT_ROW_CLONES void importanceRow(const Planes& g, int width, int height, const Window& win, int y, float* acc, float* out) {
    std::fill(acc, acc + width, 1.0f);  // the pixel itself
    for (int dy = win.lo; dy <= win.hi; ++dy) {
        if (y + dy < 0 || y + dy >= height) continue;
        for (int dx = win.lo; dx <= win.hi; ++dx)
            if (dx != 0 || dy != 0) accumulateOffset<UseN, UseP>(g, width, y, dx, dy, acc);
    }
    const float rows = float(win.inside(y, height));
    for (int x = 0; x < width; ++x) out[x] = std::max(0.0f, 1.0f - acc[x] / (rows * float(win.inside(x, width))));
}

using RowFn = void (*)(const Planes&, int, int, const Window&, int, float*, float*);

RowFn pickRow(bool useN, bool useP) {
    if (useN) return useP ? importanceRow<true, true> : importanceRow<true, false>;
    return useP ? importanceRow<false, true> : importanceRow<false, false>;
}

const float* planeOrNull(const VectorPlanes& v, int k, bool used, std::size_t pixels, const char* what) {
    if (!used) return nullptr;
    if (v.c[std::size_t(k)].size() != pixels) throw Error(std::string("importance: the ") + what + " guide does not cover the image");
    return v.c[std::size_t(k)].data();
}

}  // namespace

std::vector<float> geometryImportance(const GeometryGuides& guides, const ImportanceSettings& s) {
    if (s.window < 2 || s.window > 10)
        throw Error("importance: window " + std::to_string(s.window) + " is outside [2, 10]");
    AtrousSettings check;
    check.sigmaNormal = s.sigmaNormal, check.sigmaPosition = s.sigmaPosition;
    validate(check);
    const int width = guides.width, height = guides.height;
    const std::size_t pixels = std::size_t(width) * height;
    const bool useN = s.sigmaNormal != AtrousSettings::kOff, useP = s.sigmaPosition != AtrousSettings::kOff;
    Planes g{};
    for (int k = 0; k < 3; ++k) {
        g.n[k] = planeOrNull(guides.normal, k, useN, pixels, "normal");
        g.p[k] = planeOrNull(guides.position, k, useP, pixels, "position");
    }
    g.invN = inverseSquare(s.sigmaNormal), g.invP = inverseSquare(s.sigmaPosition);
    const Window win(s.window);
    const RowFn row = pickRow(useN, useP);
    std::vector<float> importance(pixels);
    tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& r) {
        enableFastFloatMode();  // same floating-point mode on every thread
        std::vector<float> acc(static_cast<std::size_t>(width));
        for (int y = r.begin(); y != r.end(); ++y) row(g, width, height, win, y, acc.data(), importance.data() + std::size_t(y) * width);
    });
    return importance;
}

}  // namespace weft
