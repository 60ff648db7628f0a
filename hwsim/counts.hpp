#pragma once
// Per-stage counts of the modelled pipeline, plain integers while a draw
// runs (per thread), named when they leave it:
//   fragments.generated              covered pixel centres inside the target
//   fragments.rejected.<stage>       stipple, scissor, bounds, stencil, depth_early, depth_late
//   fragments.discarded              killed by the fragment program
//   fragment_program.invocations     program runs, helper invocations of 2x2 quads included
//   fragment_program.helpers         of those, runs whose results are dropped (quad helpers, stipple kills)
//   fragment_program.cost            lock-step cost: per branch block, lanes x the longest path
//   samples.passed                   what a SAMPLES_PASSED query counts
//   pixels.written                   passed fragments that write colour (any channel enabled) or depth
//   coarse.tiles_culled              hierarchical Z/stencil tiles rejected whole
//   stats.fragment_shader_invocations   what a FRAGMENT_SHADER_INVOCATIONS query reports (the profile's
//                                       shader_invocations_counter: pixels, quads or whole stamps)
//   stats.clipping_input_primitives     primitives drawn (CLIPPING_INPUT_PRIMITIVES)
//   stats.clipping_output_primitives    primitives leaving the clipper (CLIPPING_OUTPUT_PRIMITIVES)
#include <cstdint>

#include "core/base/run/counters.hpp"

namespace weft::hwsim {

enum class Stage : int { Stipple, Scissor, Bounds, Stencil, DepthEarly, DepthLate, Count };

struct StageCounts {
    std::int64_t generated = 0;
    std::int64_t rejected[int(Stage::Count)]{};
    std::int64_t discarded = 0, invocations = 0, helpers = 0, cost = 0;
    std::int64_t samplesPassed = 0, pixelsWritten = 0, tilesCulled = 0;
    std::int64_t fragmentShaderInvocations = 0, clippingInputPrimitives = 0, clippingOutputPrimitives = 0;

    void add(const StageCounts& o);
    // Every counter by name, zeros included (tables line up across runs).
    CounterMap named() const;
};

const char* stageName(Stage s);

}  // namespace weft::hwsim
