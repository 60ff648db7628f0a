#include "plugins/host/trade/tune_search.hpp"

#include <cmath>
#include <cstdio>

#include "core/base/error.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

std::optional<double> numberOf(const std::string& text) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v)) return std::nullopt;
    return v;
}

bool isInteger(const std::string& text) { return text.find_first_not_of("0123456789") == std::string::npos && !text.empty(); }

using Setting = std::vector<std::pair<std::string, std::string>>;  // knob -> value, in knob order

std::string formatKnob(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v);
    return text;
}

// Renders every combination of the groups (planSweep), returns their results.
std::vector<SweepResult> measure(const RenderRequest& base, const std::vector<SweepGroup>& groups, const LoadedScene& first,
                                 SweepReferences& refs, const SweepOptions& options) {
    const std::vector<SweepRun> runs = planSweep(base, groups, *first.scene);
    refs.check(runs, *first.scene);
    return runSweep(runs, base, first, refs, options);
}

// The coarse pass: one group whose axes are the knobs' grids.
SweepGroup coarseGrid(const TechniqueInfo& info) {
    SweepGroup g{info.name, {}};
    for (const TradeKnob& k : info.knobs) g.axes.push_back({k.key, k.values});
    return g;
}

// One setting as a group of single-value axes.
SweepGroup groupOf(const std::string& technique, const Setting& setting) {
    SweepGroup g{technique, {}};
    for (const auto& [k, v] : setting) g.axes.push_back({k, {v}});
    return g;
}

Setting settingOf(const SweepResult& r) { return r.run.varied; }

// The grid value listed before `value` (cheaper ones come first).
std::optional<std::string> cheaperNeighbour(const TradeKnob& k, const std::string& value) {
    for (std::size_t i = 1; i < k.values.size(); ++i)
        if (k.values[i] == value) return k.values[i - 1];
    return std::nullopt;
}

struct Search {
    const TuneTarget& target;
    TuneChoice choice;
    void consider(const std::vector<SweepResult>& results) {
        for (const SweepResult& r : results) {
            ++choice.runs;
            if (!r.refused.empty()) continue;
            if (target.met(r.error)) {
                if (!choice.best || r.times.medianMs < choice.best->times.medianMs) choice.best = r;
            } else if (!choice.closest || metricAsError(r.error, target.metric) < metricAsError(choice.closest->error, target.metric)) {
                choice.closest = r;
            }
        }
    }
};

// From the cheapest passing setting, each numeric knob is bisected between
// its value and its cheaper end: a midpoint that fails becomes the cheap end,
// the fastest that passes becomes the point the next round starts from.
void bisect(const RenderRequest& base, const TechniqueInfo& info, const LoadedScene& first, SweepReferences& refs,
            const TuneOptions& options, Search& search) {
    Setting at = settingOf(*search.choice.best);
    std::vector<std::optional<std::string>> cheapEnd;
    for (std::size_t i = 0; i < at.size(); ++i) cheapEnd.push_back(cheaperNeighbour(info.knobs[i], at[i].second));
    for (int round = 0; round < options.rounds; ++round) {
        std::vector<Setting> candidates;
        std::vector<SweepGroup> groups;
        std::vector<std::size_t> knobOf;
        for (std::size_t i = 0; i < at.size(); ++i) {
            const auto mid = cheapEnd[i] ? knobMidpoint(at[i].second, *cheapEnd[i]) : std::nullopt;
            if (!mid) continue;
            candidates.push_back(at), candidates.back()[i].second = *mid, knobOf.push_back(i);
            groups.push_back(groupOf(info.name, candidates.back()));
        }
        if (candidates.empty()) return;
        const std::vector<SweepResult> results = measure(base, groups, first, refs, options.sweep);
        search.consider(results);
        const SweepResult* fastest = nullptr;
        for (std::size_t c = 0; c < results.size(); ++c) {
            if (!results[c].refused.empty() || !search.target.met(results[c].error)) cheapEnd[knobOf[c]] = candidates[c][knobOf[c]].second;
            else if (!fastest || results[c].times.medianMs < fastest->times.medianMs) fastest = &results[c];
        }
        if (fastest) at = settingOf(*fastest);
    }
}

}  // namespace

bool TuneTarget::met(const TradeError& e) const {
    const double v = metricValue(e, metric);
    return higherIsBetter(metric) ? v >= value : v <= value;
}

TuneTarget parseTuneTarget(const std::string& text) {
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos) throw Error("--target '" + text + "': expected metric=value, e.g. --target rmse=0.01");
    TuneTarget t;
    try {
        t.metric = parseTradeMetric(text.substr(0, eq));
    } catch (const Error& e) {
        throw Error("--target '" + text + "': " + e.what());
    }
    const std::optional<double> v = numberOf(text.substr(eq + 1));
    if (!v || *v < 0) throw Error("--target '" + text + "': the value must be a finite number >= 0");
    t.value = *v;
    return t;
}

std::optional<std::string> knobMidpoint(const std::string& a, const std::string& b) {
    const std::optional<double> x = numberOf(a), y = numberOf(b);
    if (!x || !y || *x <= 0 || *y <= 0) return std::nullopt;
    const double mid = std::sqrt(*x * *y);
    if (isInteger(a) && isInteger(b)) {
        const long long m = std::llround(mid);
        if (m == std::llround(*x) || m == std::llround(*y)) return std::nullopt;
        return std::to_string(m);
    }
    const std::string text = formatKnob(mid);
    return text == a || text == b ? std::nullopt : std::optional(text);
}

std::vector<TuneChoice> tuneTechniques(const RenderRequest& base, const std::vector<std::string>& names, const LoadedScene& first,
                                       SweepReferences& references, const TuneTarget& target, const TuneOptions& options) {
    std::vector<TuneChoice> choices;
    for (const std::string& name : names) {
        const TechniqueInfo& info = techniques().get(name);
        if (info.knobs.empty()) throw Error(name + " declares no speed/accuracy knobs to tune");
        Search search{target, {name, {}, {}, 0}};
        search.consider(measure(base, {coarseGrid(info)}, first, references, options.sweep));
        if (search.choice.best) bisect(base, info, first, references, options, search);
        choices.push_back(std::move(search.choice));
    }
    return choices;
}

}  // namespace weft
