#include "hwsim/replay.hpp"

#include <algorithm>
#include <cstdio>
#include <set>

#include <nlohmann/json.hpp>

namespace weft::hwsim {

ReplayRegistry& replays() {
    static ReplayRegistry registry("hwsim replay");
    return registry;
}

ReplayResult runReplay(const std::string& name, const Profile& profile, const std::map<std::string, std::string>& params) {
    const ReplayInfo& info = replays().get(name);
    return info.run(profile, info.params.parse(params));
}

CounterMap withStageCounts(const StageCounts& counts, CounterMap extra) {
    CounterMap m = counts.named();
    for (auto& [k, v] : extra) m[k] = v;
    return m;
}

std::string replayTable(const ReplayResult& result) {
    std::set<std::string, std::less<>> names;
    for (const ReplayVariant& v : result.variants)
        for (const auto& [k, n] : v.counters) names.insert(k);
    std::size_t nameWidth = 8;
    for (const std::string& n : names) nameWidth = std::max(nameWidth, n.size());
    std::vector<std::size_t> widths;
    for (const ReplayVariant& v : result.variants) widths.push_back(std::max<std::size_t>(12, v.label.size()));
    std::string out;
    char cell[128];
    std::snprintf(cell, sizeof cell, "%-*s", int(nameWidth), "counter");
    out += cell;
    for (std::size_t i = 0; i < widths.size(); ++i) {
        std::snprintf(cell, sizeof cell, "  %*s", int(widths[i]), result.variants[i].label.c_str());
        out += cell;
    }
    out += "\n";
    for (const std::string& n : names) {
        std::snprintf(cell, sizeof cell, "%-*s", int(nameWidth), n.c_str());
        out += cell;
        for (std::size_t i = 0; i < widths.size(); ++i) {
            const auto it = result.variants[i].counters.find(n);
            const long long v = it == result.variants[i].counters.end() ? 0 : it->second;
            std::snprintf(cell, sizeof cell, "  %*lld", int(widths[i]), v);
            out += cell;
        }
        out += "\n";
    }
    for (const std::string& note : result.notes) out += note + "\n";
    return out;
}

std::size_t baselineIndex(const ReplayResult& result) {
    for (std::size_t i = 0; i < result.variants.size(); ++i)
        if (result.variants[i].label == result.baseline) return i;
    return 0;
}

std::string replayPredictions(const ReplayResult& result, const Profile& profile) {
    if (result.variants.empty()) return "";
    const CostModel& model = profile.cost;
    const ReplayVariant& baseline = result.variants[baselineIndex(result)];
    const double base = predictedMs(model, baseline.counters);
    std::string out = "predicted time (" + profile.name + " cost model, " + model.calibration + "):\n";
    char line[200];
    std::snprintf(line, sizeof line, "%-16s  %12s  %s\n", "variant", "predicted ms", ("speed-up vs " + baseline.label).c_str());
    out += line;
    for (const ReplayVariant& v : result.variants) {
        const double ms = predictedMs(model, v.counters);
        std::snprintf(line, sizeof line, "%-16s  %12.3f  %8.3f\n", v.label.c_str(), ms, ms > 0 ? base / ms : 0.0);
        out += line;
    }
    return out;
}

std::string replayStatsJson(const std::string& name, const Profile& profile, const ParamSet& params,
                            const ReplayResult& result) {
    nlohmann::ordered_json j;
    j["replay"] = name;
    j["profile"] = profile.name;
    for (const auto& [k, v] : params.values()) j["params"][k] = v;
    j["variants"] = nlohmann::ordered_json::object();
    for (const ReplayVariant& v : result.variants)
        for (const auto& [k, n] : v.counters) j["variants"][v.label][k] = n;
    j["notes"] = result.notes;
    return j.dump(2) + "\n";
}

}  // namespace weft::hwsim
