#pragma once
// Runs a planned sweep in one process: each distinct framing of the scene
// (one per image aspect) is loaded once, with its BVH, and every run renders
// on it; each run repeats --repeat times (the image of the first repeat is
// measured) and is compared with its reference.
#include <optional>
#include <string>
#include <vector>

#include "core/base/run/counters.hpp"
#include "plugins/host/trade/sweep_plan.hpp"
#include "plugins/host/trade/sweep_reference.hpp"
#include "plugins/host/trade/trade_metrics.hpp"

namespace weft {

struct RunTimes {
    double medianMs = 0, minMs = 0, maxMs = 0;
};
RunTimes summarizeTimes(std::vector<double> ms);

struct SweepResult {
    SweepRun run;
    RunTimes times;               // wall time of the render: technique set-up and image
    std::vector<double> repeatMs;
    CounterMap counters;
    std::int64_t samples = 0;     // sampleCost(counters)
    TradeError error;
    std::string params;           // the technique's parameters as rendered, "k=v k=v"
    // The technique's one-line refusal of this setting (a combination of
    // values it does not render, e.g. more sub-buffers than VPLs); such a
    // run has no time or error and stays out of the fronts.
    std::string refused;
};
bool anyRendered(const std::vector<SweepResult>& results);

// A cost that does not depend on the machine: every ray traced and every
// volume sample taken (rays.*, volume.samples, fragments.shaded).
std::int64_t sampleCost(const CounterMap& counters);

struct SweepOptions {
    int repeat = 1;
    bool progress = false;  // a line per run on stderr
};

// Renders (or reads) every run's reference, each on the scene framed for
// its run's aspect, as runSweep would: the farm's --prepare.
void prepareReferences(const std::vector<SweepRun>& runs, const RenderRequest& base, const LoadedScene& first,
                       SweepReferences& references);

// `first` is the scene as `base` loads it (the one the plan was checked on).
// A run the technique refuses is recorded as refused and the sweep goes on;
// a reference that cannot be rendered stops it.
std::vector<SweepResult> runSweep(const std::vector<SweepRun>& runs, const RenderRequest& base, const LoadedScene& first,
                                  SweepReferences& references, const SweepOptions& options);

}  // namespace weft
