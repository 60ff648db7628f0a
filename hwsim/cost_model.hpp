#pragma once
// A profile's cost model: a predicted time from a replay variant's counts,
// the sum over a few counters (passes, fragments.generated,
// fragment_program.invocations, fragment_program.cost, ...) of count x
// nanoseconds per count. Fitted to measured times by
// bench/hwsim_calibrate.py; hwsim/profiles/README.md documents the key.
#include <map>
#include <string>

#include "core/base/run/counters.hpp"

namespace weft::hwsim {

struct CostModel {
    std::string calibration = "default: 1 ns per fragment_program.cost unit, nothing else (not measured)";
    std::map<std::string, double> nsPer{{"fragment_program.cost", 1.0}};  // counter -> ns per count
};

// The profile's "cost_model" object; errors name the file, the key and what is wrong.
CostModel parseCostModel(const std::string& json, const std::string& fileName);

// Predicted milliseconds of a variant; a counter the variant lacks counts zero.
double predictedMs(const CostModel& model, const CounterMap& counters);

}  // namespace weft::hwsim
