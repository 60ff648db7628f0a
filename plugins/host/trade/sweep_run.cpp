#include "plugins/host/trade/sweep_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

#include "core/base/error.hpp"
#include "core/base/run/render_monitor.hpp"

namespace weft {

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Scenes by the aspect they were framed for ("" when the request has no resolution).
class SceneCache {
public:
    explicit SceneCache(const LoadedScene& first, const RenderRequest& base) { scenes_.emplace(key(base), first); }
    const LoadedScene& sceneFor(const RenderRequest& r) {
        auto it = scenes_.find(key(r));
        if (it == scenes_.end()) it = scenes_.emplace(key(r), loadRequestScene(r)).first;
        return it->second;
    }

private:
    static std::string key(const RenderRequest& r) {
        const auto aspect = requestAspect(r);
        return aspect ? std::to_string(*aspect) : "";
    }
    std::map<std::string, LoadedScene> scenes_;
};

std::string paramsText(const RenderOutcome& out) {
    std::string text;
    for (const auto& [k, v] : out.metadata)
        if (k.rfind("weft:param:", 0) == 0) text += (text.empty() ? "" : " ") + k.substr(11) + "=" + v;
    return text;
}

void printProgress(const SweepResult& r, std::size_t done, std::size_t total, double elapsedMs) {
    const double leftS = elapsedMs / double(done) * double(total - done) / 1000;
    if (!r.refused.empty())
        return (void)std::fprintf(stderr, "sweep: run %zu of %zu  %s %s  refused: %s\n", done, total, r.run.technique.c_str(),
                                  runLabel(r.run).c_str(), r.refused.c_str());
    std::fprintf(stderr, "sweep: run %zu of %zu  %s %s  %.3g s  RMSE %.4g  (about %.0f s left)\n", done, total,
                 r.run.technique.c_str(), runLabel(r.run).c_str(), r.times.medianMs / 1000, r.error.rmse, leftS);
}

SweepResult runOne(const SweepRun& run, const LoadedScene& scene, SweepReferences& refs, int repeat) {
    const TradeReference& reference = refs.measureFor(run, scene);
    SweepResult res{run, {}, {}, {}, 0, {}, {}, {}};
    RenderOutcome first;
    try {
        for (int i = 0; i < repeat; ++i) {
            const auto t0 = std::chrono::steady_clock::now();
            RenderOutcome out = renderLoadedScene(run.request, scene);
            res.repeatMs.push_back(msSince(t0));
            if (i == 0) first = std::move(out);
        }
    } catch (const Cancelled&) {
        throw;
    } catch (const Error& e) {
        res.refused = e.what();
        return res;
    }
    res.times = summarizeTimes(res.repeatMs);
    res.counters = first.counters;
    res.samples = sampleCost(first.counters);
    res.params = paramsText(first);
    res.error = reference.measure(first.image);
    return res;
}

}  // namespace

RunTimes summarizeTimes(std::vector<double> ms) {
    if (ms.empty()) return {};
    std::sort(ms.begin(), ms.end());
    const std::size_t n = ms.size();
    const double median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
    return {median, ms.front(), ms.back()};
}

bool anyRendered(const std::vector<SweepResult>& results) {
    return std::any_of(results.begin(), results.end(), [](const SweepResult& r) { return r.refused.empty(); });
}

std::int64_t sampleCost(const CounterMap& counters) {
    std::int64_t total = 0;
    for (const auto& [name, n] : counters)
        if (name.rfind("rays.", 0) == 0 || name == "volume.samples" || name == "fragments.shaded") total += n;
    return total;
}

void prepareReferences(const std::vector<SweepRun>& runs, const RenderRequest& base, const LoadedScene& first,
                       SweepReferences& references) {
    SceneCache scenes(first, base);
    for (const SweepRun& run : runs) references.imageFor(run, scenes.sceneFor(run.request));
}

std::vector<SweepResult> runSweep(const std::vector<SweepRun>& runs, const RenderRequest& base, const LoadedScene& first,
                                  SweepReferences& references, const SweepOptions& options) {
    SceneCache scenes(first, base);
    std::vector<SweepResult> results;
    const auto start = std::chrono::steady_clock::now();
    for (const SweepRun& run : runs) {
        try {
            results.push_back(runOne(run, scenes.sceneFor(run.request), references, std::max(1, options.repeat)));
        } catch (const Cancelled&) {
            throw;
        } catch (const Error& e) {
            throw Error("sweep run " + std::to_string(run.index + 1) + " (" + run.technique + " " + runLabel(run) + "): " + e.what());
        }
        if (options.progress) printProgress(results.back(), results.size(), runs.size(), msSince(start));
    }
    return results;
}

}  // namespace weft
