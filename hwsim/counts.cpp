#include "hwsim/counts.hpp"

#include <string>

namespace weft::hwsim {

const char* stageName(Stage s) {
    static const char* names[] = {"stipple", "scissor", "bounds", "stencil", "depth_early", "depth_late"};
    return names[int(s)];
}

void StageCounts::add(const StageCounts& o) {
    generated += o.generated;
    for (int i = 0; i < int(Stage::Count); ++i) rejected[i] += o.rejected[i];
    discarded += o.discarded, invocations += o.invocations, helpers += o.helpers, cost += o.cost;
    samplesPassed += o.samplesPassed, pixelsWritten += o.pixelsWritten, tilesCulled += o.tilesCulled;
    fragmentShaderInvocations += o.fragmentShaderInvocations;
    clippingInputPrimitives += o.clippingInputPrimitives, clippingOutputPrimitives += o.clippingOutputPrimitives;
}

CounterMap StageCounts::named() const {
    CounterMap m;
    m["fragments.generated"] = generated;
    for (int i = 0; i < int(Stage::Count); ++i)
        m[std::string("fragments.rejected.") + stageName(Stage(i))] = rejected[i];
    m["fragments.discarded"] = discarded;
    m["fragment_program.invocations"] = invocations;
    m["fragment_program.helpers"] = helpers;
    m["fragment_program.cost"] = cost;
    m["samples.passed"] = samplesPassed;
    m["pixels.written"] = pixelsWritten;
    m["coarse.tiles_culled"] = tilesCulled;
    m["stats.fragment_shader_invocations"] = fragmentShaderInvocations;
    m["stats.clipping_input_primitives"] = clippingInputPrimitives;
    m["stats.clipping_output_primitives"] = clippingOutputPrimitives;
    return m;
}

}  // namespace weft::hwsim
