#pragma once
// Replays: a paper's GPU pass structure as a named kernel that drives the
// modelled pipeline under a hardware profile and reports its counts. A
// replay may compare variants (columns of the counter table); each variant
// carries the pipeline's counters plus the replay's own (volume.samples...).
// Replays register by name from their own .cpp file, like techniques, and
// declare their parameters in a ParamTable.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/base/run/counters.hpp"
#include "core/image/image.hpp"
#include "core/base/options/params.hpp"
#include "core/base/registry.hpp"
#include "hwsim/counts.hpp"
#include "hwsim/profile.hpp"

namespace weft::hwsim {

struct ReplayVariant {
    std::string label;
    CounterMap counters;
};

struct ReplayResult {
    std::vector<ReplayVariant> variants;
    std::vector<std::string> notes;  // one line each, printed under the table
    std::optional<Image> image;      // replays of a renderer return its image
    std::string baseline;            // the variant speed-ups are relative to (empty: the first)
};

struct ReplayInfo {
    std::string name;
    std::string summary;
    ParamTable params;
    std::function<ReplayResult(const Profile&, const ParamSet&)> run;
};

using ReplayRegistry = NamedRegistry<ReplayInfo>;
ReplayRegistry& replays();

struct ReplayRegistrar {
    explicit ReplayRegistrar(ReplayInfo info) { replays().add(std::move(info)); }
};

// Runs a replay by name with key=value parameters.
ReplayResult runReplay(const std::string& name, const Profile& profile, const std::map<std::string, std::string>& params);

// Counter names as rows, variants as columns.
std::string replayTable(const ReplayResult& result);
// {"replay", "profile", "params", "variants": {label: {counter: n}}, "notes"}.
std::string replayStatsJson(const std::string& name, const Profile& profile, const ParamSet& params,
                            const ReplayResult& result);

// Predicted time of each variant under the profile's cost model and its
// speed-up over the baseline variant, one line each, under a heading that
// names the model's calibration.
std::string replayPredictions(const ReplayResult& result, const Profile& profile);
// The baseline variant's index (ReplayResult::baseline, else 0).
std::size_t baselineIndex(const ReplayResult& result);

// The pipeline's counts merged with a replay's own counters.
CounterMap withStageCounts(const StageCounts& counts, CounterMap extra = {});

}  // namespace weft::hwsim
