#include "hwsim/cost_model.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/base/error.hpp"
#include "hwsim/counts.hpp"

namespace weft::hwsim {

namespace {

// The counters a term may name: every pipeline counter plus the replays' own.
const char* const kReplayCounters[] = {"passes", "texture.scattered_fetches" /* segovia.table1 */};

bool knownCounter(const std::string& name) {
    for (const char* own : kReplayCounters)
        if (name == own) return true;
    return StageCounts{}.named().count(name) > 0;
}

std::string knownCounters() {
    std::string all;
    for (const char* own : kReplayCounters) all += (all.empty() ? "" : ", ") + std::string(own);
    for (const auto& [k, v] : StageCounts{}.named()) all += ", " + k;
    return all;
}

}  // namespace

CostModel parseCostModel(const std::string& text, const std::string& fileName) {
    const std::string where = fileName + ": 'cost_model'";
    const nlohmann::json j = nlohmann::json::parse(text);
    if (!j.is_object() || j.size() != 2 || !j.contains("calibration") || !j.contains("ns_per"))
        throw Error(where + " must be an object with exactly 'calibration' (text) and 'ns_per' ({counter: ns per count})");
    if (!j["calibration"].is_string()) throw Error(where + ".calibration must be a string");
    if (!j["ns_per"].is_object() || j["ns_per"].empty()) throw Error(where + ".ns_per must be a non-empty object");
    CostModel m;
    m.calibration = j["calibration"].get<std::string>();
    m.nsPer.clear();
    for (const auto& [name, v] : j["ns_per"].items()) {
        if (!knownCounter(name)) throw Error(where + ".ns_per: unknown counter '" + name + "' (valid: " + knownCounters() + ")");
        if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0)
            throw Error(where + ".ns_per." + name + " must be a number >= 0");
        m.nsPer[name] = v.get<double>();
    }
    return m;
}

double predictedMs(const CostModel& model, const CounterMap& counters) {
    double ns = 0;
    for (const auto& [name, perCount] : model.nsPer)
        if (const auto it = counters.find(name); it != counters.end()) ns += perCount * double(it->second);
    return ns * 1e-6;
}

}  // namespace weft::hwsim
