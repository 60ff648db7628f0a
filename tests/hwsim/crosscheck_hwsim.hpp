#pragma once
// hwsim's side of the cross-checks: a case of crosscheck_cases.hpp drawn by
// the modelled pipeline under a profile, counted as weft_mesa_check counts
// a GL implementation (case_lines.hpp).
#include "hwsim/pipeline.hpp"
#include "tests/hwsim/crosscheck_cases.hpp"

namespace weft::crosscheck {

// The programs of ProgramKind as hwsim runs them.
struct CaseProgram {
    ProgramKind kind;
    void operator()(const Fragment& f, FragmentOutput& o) const {
        o.color = {1, 1, 1, 1};
        if (kind == ProgramKind::DiscardOdd) o.discard = (f.x & 1) != 0;
        if (kind == ProgramKind::WriteDepth) o.depth = f.x + 0.5f < 32.0f ? 0.25f : 0.75f;
    }
};

// Every field, the pipeline statistics included. Throws weft::Error where
// the profile lacks a feature the case uses.
inline Counts runOnHwsim(const Case& c, const Profile& profile) {
    Framebuffer fb(kSize, kSize, c.clearDepth);
    fb.stencil.assign(fb.stencil.size(), c.clearStencil);
    Pipeline pipe(fb, profile);
    for (const Pass& pass : c.passes) {
        pipe.state = pass.state;
        const ProgramTraits traits{pass.program == ProgramKind::WriteDepth, pass.program == ProgramKind::DiscardOdd, true,
                                   pass.earlyFragmentTests, pass.program != ProgramKind::Plain};
        for (std::size_t i = 0; i + 2 < pass.triangles.size(); i += 3) {
            const Vertex v[3] = {pass.triangles[i], pass.triangles[i + 1], pass.triangles[i + 2]};
            pipe.drawTriangle(v, CaseProgram{pass.program}, traits);
        }
    }
    const StageCounts& k = pipe.counts();
    Counts counts;
    counts.samplesPassed = k.samplesPassed;
    counts.invocations = k.invocations - k.helpers;
    counts.fsInvocations = k.fragmentShaderInvocations;
    counts.clipIn = k.clippingInputPrimitives, counts.clipOut = k.clippingOutputPrimitives;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            if (fb.colorAt(fb.index(x, y))[0] != 0) counts.markWritten(x, y);
    return counts;
}

}  // namespace weft::crosscheck
