#include "plugins/host/trade/sweep_plan.hpp"

#include <set>
#include <tuple>

#include "core/base/error.hpp"
#include "plugins/host/render_job.hpp"

namespace weft {

namespace {

// The render options a sweep may vary; every other key is a technique parameter.
const RenderOption* sweptRenderOption(const std::string& key) {
    if (key != "spp" && key != "seed" && key != "res" && key != "resolution") return nullptr;
    return findRenderOption(key, kOnCommandLine);
}

void applyVaried(RenderRequest& r, const std::string& key, const std::string& value) {
    if (const RenderOption* option = sweptRenderOption(key)) {
        applyRenderOption(r, *option, value, "--vary " + key);
        return;
    }
    r.sets.push_back(key + "=" + value);
}

std::vector<SweepAxis> groupAxes(const SweepGroup& group, const std::vector<SweepAxis>& shared) {
    std::vector<SweepAxis> axes = shared;
    axes.insert(axes.end(), group.axes.begin(), group.axes.end());
    std::set<std::string> seen;
    for (const SweepAxis& a : axes)
        if (!seen.insert(a.key == "resolution" ? "res" : a.key).second)
            throw Error("--vary " + a.key + " is given twice for " + group.technique.value_or("the scene's technique"));
    return axes;
}

// One run per combination, the last axis fastest.
void addCombinations(const RenderRequest& base, const std::vector<SweepAxis>& axes, std::vector<SweepRun>& runs) {
    std::vector<std::size_t> at(axes.size(), 0);
    while (true) {
        SweepRun run;
        run.request = base;
        for (std::size_t i = 0; i < axes.size(); ++i) {
            run.varied.emplace_back(axes[i].key, axes[i].values[at[i]]);
            applyVaried(run.request, axes[i].key, axes[i].values[at[i]]);
        }
        runs.push_back(std::move(run));
        std::size_t i = axes.size();
        while (i > 0 && ++at[i - 1] == axes[i - 1].values.size()) at[--i] = 0;
        if (i == 0) return;
    }
}

// The render's own checks, with the run's varied values named.
void checkRun(SweepRun& run, const Scene& scene) {
    try {
        validateRequest(run.request);
        const CheckedRender checked = checkRender(run.request, scene);
        run.technique = checked.effective.technique;
        run.width = checked.effective.resolution.width, run.height = checked.effective.resolution.height;
    } catch (const Error& e) {
        throw Error("--vary " + runLabel(run) + ": " + e.what());
    }
}

}  // namespace

SweepAxis parseVary(const std::string& text) {
    const std::size_t eq = text.find('=');
    SweepAxis axis;
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
        throw Error("--vary '" + text + "': expected key=value[,value...], e.g. --vary step=0.25,0.5,1");
    axis.key = text.substr(0, eq);
    for (std::size_t start = eq + 1;;) {
        const std::size_t comma = text.find(',', start);
        axis.values.push_back(text.substr(start, comma - start));
        if (axis.values.back().empty()) throw Error("--vary '" + text + "': an empty value");
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return axis;
}

std::vector<SweepRun> planSweep(const RenderRequest& base, const std::vector<SweepGroup>& groups, const Scene& scene) {
    std::vector<SweepAxis> shared;
    std::vector<SweepGroup> techniqueGroups;
    for (const SweepGroup& g : groups) {
        if (g.technique) techniqueGroups.push_back(g);
        else shared.insert(shared.end(), g.axes.begin(), g.axes.end());
    }
    if (techniqueGroups.empty()) techniqueGroups.push_back(SweepGroup{});
    std::vector<SweepRun> runs;
    for (const SweepGroup& g : techniqueGroups) {
        RenderRequest r = base;
        if (g.technique) r.technique = g.technique;
        addCombinations(r, groupAxes(g, shared), runs);
    }
    for (std::size_t i = 0; i < runs.size(); ++i) {
        runs[i].index = int(i);
        checkRun(runs[i], scene);
    }
    return runs;
}

std::string runLabel(const SweepRun& run) {
    std::string label;
    for (const auto& [k, v] : run.varied) label += (label.empty() ? "" : " ") + k + "=" + v;
    return label.empty() ? "defaults" : label;
}

}  // namespace weft
