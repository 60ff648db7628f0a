// weft tune SCENE --target rmse=0.01 [--metric M] [--technique T ...]
//           [--reference REF.exr|auto] [--json CHOICE.json]
// Searches each technique's speed/accuracy knobs (tune_search.hpp) and
// prints the cheapest setting that meets the target as a ready `weft render`
// command line, with its measured time and error, and the best setting of
// every other technique for comparison.
#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/base/files/atomic_file.hpp"
#include "core/base/error.hpp"
#include "plugins/host/command_line_monitor.hpp"
#include "core/scene/scene.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/trade/sweep_report.hpp"
#include "plugins/host/trade/trade_options.hpp"
#include "plugins/host/trade/tune_search.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

namespace fs = std::filesystem;

struct TuneCommand {
    std::string input, target, metric, reference = "auto", cacheDir, json;
    std::vector<std::string> techniques;
    TradeRenderOptions renderOptions;
    int repeat = 1, rounds = 3;
};

TuneTarget targetOf(const TuneCommand& c) {
    if (c.target.find('=') != std::string::npos) {
        const TuneTarget t = parseTuneTarget(c.target);
        if (!c.metric.empty() && parseTradeMetric(c.metric) != t.metric)
            throw Error("--target " + c.target + " and --metric " + c.metric + " name different metrics");
        return t;
    }
    return parseTuneTarget((c.metric.empty() ? "rmse" : c.metric) + "=" + c.target);
}

// Automatic references live in the user's cache, shared by every tune.
std::string cacheDirOf(const TuneCommand& c) {
    if (!c.cacheDir.empty()) return c.cacheDir;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "weft" / "references").string();
    if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache" / "weft" / "references").string();
    return (fs::temp_directory_path() / "weft-references").string();
}

// Without --technique: the scene's technique and those measured against the
// same converged reference (its family), so their errors compare.
std::vector<std::string> techniquesOf(const TuneCommand& c, const RenderRequest& base, const Scene& scene) {
    if (!c.techniques.empty()) return c.techniques;
    const std::string own = effectiveRender(base, scene.render).technique;
    const std::string family = techniques().get(own).reference.technique;
    std::vector<std::string> names{own};
    for (const TechniqueInfo* t : techniques().all())
        if (t->name != own && !family.empty() && t->reference.technique == family &&
            !t->knobs.empty()) {
            try {
                checkTechniqueContent(*t, scene);
                names.push_back(t->name);
            } catch (const Error&) {
            }
        }
    return names;
}

std::string shellWord(const std::string& s) {
    if (s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-/=:,+@") == std::string::npos) return s;
    std::string q = "'";
    for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return q + "'";
}

std::string renderCommand(const SweepRun& run) {
    const RenderRequest& r = run.request;
    std::string cmd = "weft render " + shellWord(r.input) + " --technique " + run.technique;
    cmd += " --res " + std::to_string(run.width) + "x" + std::to_string(run.height);
    if (r.spp) cmd += " --spp " + std::to_string(*r.spp);
    if (r.seed) cmd += " --seed " + std::to_string(*r.seed);
    if (!r.grid.empty()) cmd += " --grid " + shellWord(r.grid);
    for (const std::string& kv : r.sets) cmd += " --set " + shellWord(kv);
    return cmd + " -o out.exr";
}

std::string summary(const SweepResult& r, const TuneTarget& t) {
    char text[256];
    std::snprintf(text, sizeof text, "%s %.4g, %.3g s, %lld samples (%s)", tradeMetricName(t.metric), metricValue(r.error, t.metric),
                  r.times.medianMs / 1000, (long long)r.samples, runLabel(r.run).c_str());
    return text;
}

nlohmann::ordered_json resultJson(const SweepResult& r) {
    nlohmann::ordered_json j{{"technique", r.run.technique}, {"command", renderCommand(r.run)}};
    for (const auto& [k, v] : r.run.varied) j["settings"][k] = v;
    j["time_ms"] = r.times.medianMs;
    j["samples"] = r.samples;
    j["error"] = tradeErrorJson(r.error);
    return j;
}

const SweepResult* cheapestOverall(const std::vector<TuneChoice>& choices) {
    const SweepResult* best = nullptr;
    for (const TuneChoice& c : choices)
        if (c.best && (!best || c.best->times.medianMs < best->times.medianMs)) best = &*c.best;
    return best;
}

void writeChoice(const std::string& path, const std::vector<TuneChoice>& choices, const TuneTarget& t) {
    const SweepResult* best = cheapestOverall(choices);
    nlohmann::ordered_json j{{"target", {{"metric", tradeMetricName(t.metric)}, {"value", t.value}}}, {"met", best != nullptr}};
    if (best) j["choice"] = resultJson(*best);
    j["techniques"] = nlohmann::ordered_json::array();
    for (const TuneChoice& c : choices) {
        nlohmann::ordered_json e{{"technique", c.technique}, {"runs", c.runs}, {"met", c.best.has_value()}};
        if (c.best) e["best"] = resultJson(*c.best);
        if (c.closest && !c.best) e["closest"] = resultJson(*c.closest);
        j["techniques"].push_back(e);
    }
    writeTextAtomically(path, j.dump(2) + "\n", "--json");
}

void printChoices(const std::vector<TuneChoice>& choices, const TuneTarget& t) {
    const SweepResult* best = cheapestOverall(choices);
    const char* op = higherIsBetter(t.metric) ? ">=" : "<=";
    if (best) {
        std::printf("cheapest setting with %s %s %g: %s\n  %s\n", tradeMetricName(t.metric), op, t.value, summary(*best, t).c_str(),
                    renderCommand(best->run).c_str());
    } else {
        std::printf("no setting measured meets %s %s %g\n", tradeMetricName(t.metric), op, t.value);
    }
    for (const TuneChoice& c : choices) {
        if (c.best && &*c.best == best) continue;
        if (c.best) std::printf("  %-28s best: %s\n", c.technique.c_str(), summary(*c.best, t).c_str());
        else if (c.closest) std::printf("  %-28s none meets it; closest: %s\n", c.technique.c_str(), summary(*c.closest, t).c_str());
    }
}

void runTuneCommand(const TuneCommand& c) {
    const TuneTarget target = targetOf(c);
    const RenderRequest base = c.renderOptions.request(c.input);
    if (!c.json.empty()) checkOutputPath(c.json, "--json");
    tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, effectiveThreads(base.threads));
    const LoadedScene first = loadRequestScene(base);
    const std::vector<std::string> names = techniquesOf(c, base, *first.scene);
    for (const std::string& n : names)
        if (techniques().get(n).knobs.empty()) throw Error(n + " declares no speed/accuracy knobs to tune");
    SweepReferences references(c.reference, cacheDirOf(c));
    const std::vector<TuneChoice> choices =
        tuneTechniques(base, names, first, references, target, {c.rounds, {c.repeat, stderrIsTerminal()}});
    printChoices(choices, target);
    if (!c.json.empty()) writeChoice(c.json, choices, target);
}

const CommandRegistrar registrar{{"tune", 41, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("tune", "find the cheapest setting of each technique's speed/accuracy knobs that meets an error "
                                           "target, printed as a weft render command line");
    auto c = std::make_shared<TuneCommand>();
    cmd->add_option("input", c->input, "scene (.json), bare .vdb or builtin:NAME")->required();
    cmd->add_option("--target", c->target, "metric=value the render must meet, e.g. rmse=0.01 (or a value with --metric)")->required();
    cmd->add_option("--metric", c->metric, "rmse, relmse, psnr, ssim, flip or maxabs (default: the target's, else rmse)");
    cmd->add_option("--technique", c->techniques, "techniques to tune (repeatable; default: the scene's and its family's)")
        ->allow_extra_args(false);
    cmd->add_option("--reference", c->reference, "reference image (.exr), or auto: each technique's converged render (default)");
    cmd->add_option("--cache", c->cacheDir, "folder of automatic references (default: ~/.cache/weft/references)");
    cmd->add_option("--json", c->json, "write the choice (technique, settings, time, error) as JSON");
    cmd->add_option("--repeat", c->repeat, "renders per setting; times are their median")->check(CLI::Range(1, 1000));
    cmd->add_option("--rounds", c->rounds, "bisection rounds after the coarse grid")->check(CLI::Range(0, 20));
    c->renderOptions.install(*cmd);
    cmd->callback([c] { runTuneCommand(*c); });
}}};

}  // namespace

}  // namespace weft
