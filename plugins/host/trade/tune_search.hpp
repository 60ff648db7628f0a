#pragma once
// weft tune's search: the cheapest setting of each technique's
// speed/accuracy knobs (TechniqueInfo::knobs) whose error meets a target.
// A coarse pass renders every combination of the knobs' grids; then, from
// the cheapest setting that meets the target, each numeric knob is bisected
// toward its next cheaper grid value (geometric midpoints; integers
// rounded), keeping what still meets the target, for a few rounds.
#include <optional>
#include <string>
#include <vector>

#include "plugins/host/trade/sweep_run.hpp"

namespace weft {

struct TuneTarget {
    TradeMetric metric = TradeMetric::Rmse;
    double value = 0;
    bool met(const TradeError& e) const;
};
// "rmse=0.01" (the metric may be given apart, as --metric); throws naming the text.
TuneTarget parseTuneTarget(const std::string& text);

struct TuneChoice {
    std::string technique;
    std::optional<SweepResult> best;  // the cheapest run that meets the target; none when no run does
    std::optional<SweepResult> closest;  // when none does: the run with the least error
    int runs = 0;                     // renders measured for this technique
};

struct TuneOptions {
    int rounds = 3;  // bisection rounds after the coarse pass
    SweepOptions sweep;
};

// One choice per technique, in the order given.
std::vector<TuneChoice> tuneTechniques(const RenderRequest& base, const std::vector<std::string>& names, const LoadedScene& first,
                                       SweepReferences& references, const TuneTarget& target, const TuneOptions& options);

// The knob's value halfway (geometrically) between a and b, or nullopt when
// there is none strictly between them (integers next to each other, text).
std::optional<std::string> knobMidpoint(const std::string& a, const std::string& b);

}  // namespace weft
