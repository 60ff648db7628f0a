#pragma once
// The fixed-function state of the modelled GL fragment pipeline: the
// per-fragment tests and operations in the order GL applies them, with GL's
// meanings (glPolygonStipple, glScissor, glDepthBoundsEXT, glStencilFunc /
// glStencilOp / glStencilMask, glDepthFunc / glDepthMask, glBlendFunc,
// glColorMask). Window coordinates as in GL: origin at the lower left,
// pixel (x, y) covers [x, x+1) x [y, y+1), its centre at (x+0.5, y+0.5).
#include <array>
#include <cstdint>

namespace weft::hwsim {

enum class CompareFunc : std::uint8_t { Never, Less, Equal, LessEqual, Greater, NotEqual, GreaterEqual, Always };
enum class StencilOp : std::uint8_t { Keep, Zero, Replace, Incr, Decr, Invert, IncrWrap, DecrWrap };
enum class BlendFactor : std::uint8_t { Zero, One, SrcAlpha, OneMinusSrcAlpha, DstAlpha, OneMinusDstAlpha };

// 32x32 mask; bit x of rows[y] keeps window pixels with x mod 32 == x and
// y mod 32 == y (rows[0] is the bottom row, as GL unpacks the first row).
struct StippleState {
    bool enabled = false;
    std::array<std::uint32_t, 32> rows{};
    // The pattern that keeps pixels with x mod n == i and y mod n == j (n divides 32).
    static std::array<std::uint32_t, 32> interleaved(int n, int i, int j) {
        std::array<std::uint32_t, 32> rows{};
        for (int y = j; y < 32; y += n)
            for (int x = i; x < 32; x += n) rows[y] |= 1u << x;
        return rows;
    }
};

struct ScissorState {
    bool enabled = false;
    int x = 0, y = 0, width = 0, height = 0;
};

// EXT_depth_bounds_test: keeps a fragment when the depth already STORED at
// its pixel lies in [zmin, zmax] (both inclusive); the fragment's own depth
// plays no part.
struct DepthBoundsState {
    bool enabled = false;
    float zmin = 0, zmax = 1;
};

struct StencilState {
    bool enabled = false;
    CompareFunc func = CompareFunc::Always;
    std::uint8_t ref = 0, valueMask = 0xff, writeMask = 0xff;
    StencilOp sfail = StencilOp::Keep, dpfail = StencilOp::Keep, dppass = StencilOp::Keep;
};

struct DepthState {
    bool enabled = false;
    CompareFunc func = CompareFunc::Less;
    bool writeMask = true;
};

struct BlendState {
    bool enabled = false;
    BlendFactor src = BlendFactor::One, dst = BlendFactor::Zero;  // equation: ADD
};

struct PipelineState {
    StippleState stipple;
    ScissorState scissor;
    DepthBoundsState bounds;
    StencilState stencil;
    DepthState depth;
    BlendState blend;
    std::array<bool, 4> colorMask{true, true, true, true};
};

// Set lanes of a 2x2 quad mask (4 bits); a table, as the baseline x86-64
// target has no popcount instruction and std::popcount becomes a call.
inline int lanes(unsigned mask4) {
    constexpr int bits[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
    return bits[mask4 & 15u];
}

// GL comparison "incoming func stored".
inline bool compare(CompareFunc f, float a, float b) {
    switch (f) {
        case CompareFunc::Never: return false;
        case CompareFunc::Less: return a < b;
        case CompareFunc::Equal: return a == b;
        case CompareFunc::LessEqual: return a <= b;
        case CompareFunc::Greater: return a > b;
        case CompareFunc::NotEqual: return a != b;
        case CompareFunc::GreaterEqual: return a >= b;
        case CompareFunc::Always: return true;
    }
    return true;
}

// Direction of a depth function: -1 keeps nearer (LESS, LEQUAL), +1 keeps
// farther (GREATER, GEQUAL), 0 has none (hierarchical Z keeps working).
inline int depthDirection(CompareFunc f) {
    if (f == CompareFunc::Less || f == CompareFunc::LessEqual) return -1;
    if (f == CompareFunc::Greater || f == CompareFunc::GreaterEqual) return 1;
    return 0;
}

// The stencil value after op (8-bit buffer): Incr/Decr saturate, *Wrap wrap.
inline std::uint8_t applyStencilOp(StencilOp op, std::uint8_t value, std::uint8_t ref) {
    switch (op) {
        case StencilOp::Keep: return value;
        case StencilOp::Zero: return 0;
        case StencilOp::Replace: return ref;
        case StencilOp::Incr: return value == 0xff ? value : std::uint8_t(value + 1);
        case StencilOp::Decr: return value == 0 ? value : std::uint8_t(value - 1);
        case StencilOp::Invert: return std::uint8_t(~value);
        case StencilOp::IncrWrap: return std::uint8_t(value + 1);
        case StencilOp::DecrWrap: return std::uint8_t(value - 1);
    }
    return value;
}

// Only the bits of writeMask change.
inline std::uint8_t maskedStencilWrite(std::uint8_t old, std::uint8_t value, std::uint8_t writeMask) {
    return std::uint8_t((old & ~writeMask) | (value & writeMask));
}

inline bool stencilPasses(const StencilState& s, std::uint8_t stored) {
    return compare(s.func, float(s.ref & s.valueMask), float(stored & s.valueMask));
}

}  // namespace weft::hwsim
