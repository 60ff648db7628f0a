#pragma once
// Small pass lists rendered both by Mesa (tests/hwsim/mesa_check.cpp, a
// separate program so that each Gallium driver runs in its own process) and
// by hwsim (mesa_crosscheck_test.cpp), whose counts must agree exactly.
// Header-only: the GL program links no weft library.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "hwsim/gl_state.hpp"
#include "hwsim/raster.hpp"

namespace weft::crosscheck {

using namespace weft::hwsim;

constexpr int kSize = 64;  // target width and height (a power of two: exact NDC round trips)

// Every program increments an atomic counter first (so the counter is the
// number of non-helper invocations), then:
enum class ProgramKind {
    Plain,       // writes white
    DiscardOdd,  // discards pixels with odd x
    WriteDepth,  // gl_FragDepth = x < 32 ? 0.25 : 0.75
};

struct Pass {
    PipelineState state;
    std::vector<Vertex> triangles;  // three vertices each, window coordinates
    ProgramKind program = ProgramKind::Plain;
    bool earlyFragmentTests = false;
};

struct Case {
    std::string name;
    float clearDepth = 1;
    std::uint8_t clearStencil = 0;
    std::vector<Pass> passes;
    bool needsBounds = false;
    bool slopedEdges = false;  // random triangles (softpipe's scanline snapping differs there)
};

// What both sides report for a case. The pipeline statistics are -1 where
// the GL implementation does not offer ARB_pipeline_statistics_query.
struct Counts {
    long long samplesPassed = 0, invocations = 0, written = 0;
    long long fsInvocations = -1, clipIn = -1, clipOut = -1;  // FRAGMENT_SHADER_INVOCATIONS, CLIPPING_INPUT/OUTPUT_PRIMITIVES
    std::uint64_t writtenHash = 1469598103934665603ull;  // FNV-1a over written pixel indices
    void markWritten(int x, int y) {
        ++written;
        for (int shift = 0; shift < 32; shift += 8) writtenHash = (writtenHash ^ ((std::uint32_t(y * kSize + x) >> shift) & 0xff)) * 1099511628211ull;
    }
};

inline std::vector<Vertex> rect(float x0, float y0, float x1, float y1, float z) {
    return {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y0, z}, {x1, y1, z}, {x0, y1, z}};
}

inline std::vector<Vertex> operator+(std::vector<Vertex> a, const std::vector<Vertex>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

inline PipelineState depthState(CompareFunc f, bool write) {
    PipelineState s;
    s.depth = {true, f, write};
    return s;
}

inline std::vector<Case> cases() {
    std::vector<Case> all;
    // Centres on edges (fill rule), shared diagonals, a sloped triangle.
    const std::vector<Vertex> edgy = std::vector<Vertex>{{0.5f, 0.5f, 0.5f}, {40.5f, 0.5f, 0.5f}, {0.5f, 40.5f, 0.5f},
                                                         {3.5f, 5.5f, 0.25f}, {60.5f, 20.5f, 0.25f}, {20.5f, 62.5f, 0.25f}} +
                                     rect(10, 10, 50.5f, 30.5f, 0.75f);
    all.push_back({"raster_depth_less", 1, 0, {{depthState(CompareFunc::Less, true), edgy}}});

    PipelineState stipple;
    stipple.stipple = {true, StippleState::interleaved(4, 1, 2)};
    PipelineState stipple2;
    stipple2.stipple.enabled = true;
    for (int y = 0; y < 32; ++y) stipple2.stipple.rows[y] = 0x9e3779b9u * std::uint32_t(y + 1);
    all.push_back({"stipple", 1, 0, {{stipple, rect(0, 0, 64, 64, 0.5f)}, {stipple2, edgy}}});

    PipelineState stippleDepth = depthState(CompareFunc::Less, true);
    stippleDepth.stipple = {true, StippleState::interleaved(2, 0, 1)};
    all.push_back({"stipple_depth", 0.5f, 0, {{stippleDepth, rect(0, 0, 64, 64, 0.75f) + rect(0, 0, 32, 32, 0.25f)}}});

    PipelineState scissor;
    scissor.scissor = {true, 5, 7, 20, 13};
    all.push_back({"scissor", 1, 0, {{scissor, rect(0, 0, 64, 64, 0.5f) + edgy}}});

    PipelineState mark, test, count;
    mark.stencil = {true, CompareFunc::Always, 3, 0xff, 0xff, StencilOp::Keep, StencilOp::Keep, StencilOp::Replace};
    test.stencil = {true, CompareFunc::Equal, 3, 0x0f, 0xff, StencilOp::DecrWrap, StencilOp::Keep, StencilOp::IncrWrap};
    count.stencil = {true, CompareFunc::Less, 2, 0xff, 0x7f, StencilOp::Invert, StencilOp::Keep, StencilOp::Incr};
    all.push_back({"stencil", 1, 0xfe, {{mark, rect(8, 8, 40, 40, 0.5f)}, {test, edgy}, {count, rect(0, 0, 64, 64, 0.5f)}}});

    for (CompareFunc f : {CompareFunc::Less, CompareFunc::Greater})
        for (bool write : {true, false}) {
            const std::string name = std::string("depth_") + (f == CompareFunc::Less ? "less" : "greater") + (write ? "_write" : "_nowrite");
            all.push_back({name, 0.5f, 0, {{depthState(f, write), rect(0, 0, 48, 48, 0.25f) + rect(16, 16, 64, 64, 0.75f) + edgy}}});
        }

    Pass discard{depthState(CompareFunc::Less, true), rect(0, 0, 64, 40, 0.5f) + rect(20, 20, 60, 60, 0.25f), ProgramKind::DiscardOdd};
    all.push_back({"discard", 1, 0, {discard, {depthState(CompareFunc::Less, true), rect(0, 0, 64, 64, 0.375f)}}});
    Pass discardEft = discard;
    discardEft.earlyFragmentTests = true;
    all.push_back({"discard_early_tests", 1, 0, {discardEft, {depthState(CompareFunc::Less, true), rect(0, 0, 64, 64, 0.375f)}}});

    Pass writeDepth{depthState(CompareFunc::Less, true), rect(0, 0, 64, 64, 0.1f), ProgramKind::WriteDepth};
    all.push_back({"write_depth", 0.5f, 0, {writeDepth, {depthState(CompareFunc::Less, false), rect(0, 0, 64, 64, 0.5f)}}});

    Pass eft{depthState(CompareFunc::Less, true), rect(0, 0, 48, 48, 0.25f) + rect(16, 16, 64, 64, 0.75f)};
    eft.earlyFragmentTests = true;
    all.push_back({"early_fragment_tests", 0.5f, 0, {eft}});

    PipelineState bounds = depthState(CompareFunc::Always, false);
    bounds.bounds = {true, 0.25f, 0.5f};
    Case b{"depth_bounds", 1, 0, {{depthState(CompareFunc::Always, true), rect(0, 0, 32, 64, 0.25f) + rect(32, 0, 64, 32, 0.5f)},
                                   {bounds, rect(0, 0, 64, 64, 0.9f)}}};
    b.needsBounds = true;
    all.push_back(b);
    return all;
}

// Deterministic random pass lists: every state combination the cases above
// do not spell out. Vertices on a quarter-pixel grid, constant depth per
// triangle in eighths (exact on both sides).
class CaseRandom {
public:
    explicit CaseRandom(std::uint64_t seed) : state_(seed) {}
    std::uint32_t next(std::uint32_t n) {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return std::uint32_t((z ^ (z >> 31)) % n);
    }
    bool chance(std::uint32_t percent) { return next(100) < percent; }

private:
    std::uint64_t state_;
};

inline Pass randomPass(CaseRandom& r, bool& needsBounds, bool sloped) {
    Pass p;
    PipelineState& s = p.state;
    if (r.chance(50)) {
        const std::uint8_t masks[] = {0xff, 0x0f, 0x03, 0x00};
        s.stencil = {true, CompareFunc(r.next(8)), std::uint8_t(r.next(8)), masks[r.next(3)], masks[r.next(4)],
                     StencilOp(r.next(8)), StencilOp(r.next(8)), StencilOp(r.next(8))};
    }
    if (r.chance(70)) s.depth = {true, CompareFunc(r.next(8)), r.chance(60)};
    if (r.chance(20)) s.scissor = {true, int(r.next(40)), int(r.next(40)), int(r.next(40)), int(r.next(40))};
    if (r.chance(20)) {
        s.stipple.enabled = true;
        for (auto& row : s.stipple.rows) row = r.next(0xffffffffu) | (r.next(2) << 31);
    }
    if (r.chance(15)) {
        const float a = float(r.next(9)) / 8, b = float(r.next(9)) / 8;
        s.bounds = {true, std::min(a, b), std::max(a, b)};
        needsBounds = true;
    }
    p.program = ProgramKind(r.next(3));
    p.earlyFragmentTests = p.program != ProgramKind::WriteDepth && r.chance(25);
    const int primitives = 1 + int(r.next(3));
    for (int t = 0; t < primitives; ++t) {
        const float z = float(r.next(9)) / 8;
        auto coordinate = [&] { return float(r.next(257)) / 4; };  // inside the target: no clipping
        if (sloped)
            for (int v = 0; v < 3; ++v) p.triangles.push_back({coordinate(), coordinate(), z});
        else {
            const float x0 = coordinate(), y0 = coordinate(), x1 = coordinate(), y1 = coordinate();
            for (const Vertex& v : rect(std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1), z)) p.triangles.push_back(v);
        }
    }
    return p;
}

// Random triangles (sloped) or axis-aligned rectangles (two triangles each).
inline std::vector<Case> randomCases(int count, std::uint64_t seed, bool sloped) {
    CaseRandom r(seed);
    std::vector<Case> all;
    for (int i = 0; i < count; ++i) {
        Case c{std::string(sloped ? "random_tri_" : "random_rect_") + std::to_string(i), float(r.next(9)) / 8, std::uint8_t(r.next(8)), {}};
        c.slopedEdges = sloped;
        const int passes = 1 + int(r.next(3));
        for (int k = 0; k < passes; ++k) c.passes.push_back(randomPass(r, c.needsBounds, sloped));
        all.push_back(std::move(c));
    }
    return all;
}

inline std::vector<Case> allCases() {
    std::vector<Case> all = cases();
    for (Case& c : randomCases(60, 2024, true)) all.push_back(std::move(c));
    for (Case& c : randomCases(60, 2025, false)) all.push_back(std::move(c));
    return all;
}

}  // namespace weft::crosscheck
