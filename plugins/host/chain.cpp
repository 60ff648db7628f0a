// The chain of plugins/host/chain.hpp: the render, its steps, and running them frame by frame.
#include "plugins/host/chain.hpp"

#include "core/base/files/atomic_file.hpp"
#include "core/base/error.hpp"
#include "core/base/options/frames.hpp"

namespace weft {

namespace {

struct ChainState {
    std::vector<RenderRequest> renders;
    std::vector<ChainStep> steps;
};

ChainState& state() {
    static ChainState s;
    return s;
}

// Files every step writes, checked for all frames before the first render.
void checkStepOutputs(const std::vector<RenderRequest>& renders) {
    for (const ChainStep& step : state().steps) {
        if (!step.writes) continue;
        if (renders.size() > 1 && !hasFrameWildcard(*step.writes))
            throw Error("'" + step.name + "': '" + *step.writes + "' has no frame number (# = 4 digits, @ = 1 digit) for " +
                        std::to_string(renders.size()) + " frames");
        for (const RenderRequest& r : renders)
            checkOutputPath(r.frame ? expandFrameName(*step.writes, *r.frame) : *step.writes, step.name);
    }
}

bool anythingWritten(const std::vector<RenderRequest>& renders) {
    for (const ChainStep& step : state().steps)
        if (step.writes) return true;
    return !renders.front().output.empty() || !renders.front().preview.empty() || !renders.front().stats.empty();
}

}  // namespace

void setChainRender(std::vector<RenderRequest> renders) {
    if (!state().renders.empty()) throw Error("one render per command line: chain its steps after it");
    state().renders = std::move(renders);
}

void addChainStep(ChainStep step) {
    if (state().renders.empty()) throw Error("'" + step.name + "' needs an image: put it after a render on the same command line");
    state().steps.push_back(std::move(step));
}

bool chainHasRender() { return !state().renders.empty(); }

int runChain() {
    const std::vector<RenderRequest>& renders = state().renders;
    if (!anythingWritten(renders)) throw Error("nothing written: give render -o FILE.exr, --preview, or a 'write' step");
    checkStepOutputs(renders);
    return runRenders(renders, [](const RenderRequest& r, RenderOutcome& out) {
        if (state().steps.empty()) return;
        ChainImage image{std::move(out.image), std::move(out.metadata), out.window, r.frame, {}};
        for (const ChainStep& step : state().steps) step.apply(image);
    });
}

std::string framePath(const std::string& name, const ChainImage& in) {
    return in.frame ? expandFrameName(name, *in.frame) : name;
}

}  // namespace weft
