#pragma once
// A sweep's results as files: sweep.csv (one row per run), sweep.json (the
// same with every repeat's time), sweep.md (a Markdown table for a README)
// and the Pareto fronts of time and of samples against the chosen metric.
// Each file is written to a temporary name and renamed.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "plugins/host/trade/sweep_run.hpp"

namespace weft {

// The error metrics as JSON, the form sweep.json and tune's --json share.
nlohmann::ordered_json tradeErrorJson(const TradeError& e);

struct SweepFronts {
    std::vector<bool> byTime, bySamples;  // per result: on that front
};
SweepFronts sweepFronts(const std::vector<SweepResult>& results, TradeMetric metric);

struct SweepReportInfo {
    std::string scene, reference;  // as given
    TradeMetric metric = TradeMetric::Rmse;
    int repeat = 1;
};

void writeSweepCsv(const std::string& path, const std::vector<SweepResult>& results, const SweepFronts& fronts);
void writeSweepJson(const std::string& path, const std::vector<SweepResult>& results, const SweepFronts& fronts,
                    const SweepReportInfo& info);
// The farm form (weft sweep --run K / --merge): one run's result in its own
// file, DIR/runs/run-K.json, with what the merge needs to write the tables.
struct SweepRunFile {
    SweepResult result;
    int runCount = 0;
    SweepReportInfo info;
};
void writeSweepRunJson(const std::string& path, const SweepRunFile& file);
SweepRunFile readSweepRunJson(const std::string& path);  // throws naming the file and what is missing

void writeSweepMarkdown(const std::string& path, const std::vector<SweepResult>& results, const SweepFronts& fronts,
                        const SweepReportInfo& info);

}  // namespace weft
