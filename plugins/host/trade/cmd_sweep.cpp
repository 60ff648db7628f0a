// weft sweep SCENE [--technique T] --vary key=a,b,c [--vary ...] [--technique T2 --vary ...]
//            --reference REF.exr|auto [--repeat N] [--metric M] -o DIR
// On a farm: --list (the runs), --prepare (the references), --run K (one
// run's file in DIR/runs/), then weft sweep --merge -o DIR.
// Renders every combination in one process (the scene and its BVH loaded
// once), measures time, samples and the error against the reference, and
// writes DIR/sweep.csv, sweep.json, sweep.md and the Pareto plot sweep.png.
#include <tbb/global_control.h>

#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "core/base/files/atomic_file.hpp"
#include "core/base/error.hpp"
#include "plugins/host/command_line_monitor.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/trade/sweep_report.hpp"
#include "plugins/host/trade/trade_options.hpp"

namespace weft {

namespace {

namespace fs = std::filesystem;

struct SweepCommand {
    std::string input, outDir, reference, metric = "rmse";
    TradeRenderOptions renderOptions;
    std::vector<SweepGroup> groups{SweepGroup{}};  // the first: --vary before any --technique
    int repeat = 1;
    bool plot = true;
    // The farm form: list the runs, render the references, render one run, merge the runs' files.
    bool list = false, prepare = false, merge = false;
    int only = 0;
};

// The plot is drawn by pipelines/sweep_plot.py with Debian's matplotlib; a
// machine without it still gets the tables.
void drawPlot(const std::string& dir) {
    const char* env = std::getenv("WEFT_PIPELINES_DIR");
    const std::string script = (fs::path(env ? env : WEFT_PIPELINES_DIR) / "sweep_plot.py").string();
    const std::string cmd = "/usr/bin/python3 '" + script + "' '" + dir + "/sweep.json' '" + dir + "/sweep.png'";
    if (!fs::exists(script) || std::system(cmd.c_str()) != 0)
        std::fprintf(stderr, "weft: warning: no plot drawn (%s needs /usr/bin/python3 with matplotlib); the tables are written\n",
                     script.c_str());
}

void createOutputFolder(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) throw Error("-o '" + dir + "': cannot create the folder (" + ec.message() + ")");
    checkOutputPath((fs::path(dir) / "sweep.csv").string(), "-o");
}

std::string path(const SweepCommand& c, const std::string& name) { return (fs::path(c.outDir) / name).string(); }

void writeReports(const SweepCommand& c, const std::vector<SweepResult>& results, const SweepReportInfo& info) {
    if (!anyRendered(results))
        throw Error("every run of the sweep was refused; the first: " + results.front().run.technique + " " + runLabel(results.front().run) +
                    ": " + results.front().refused);
    const SweepFronts fronts = sweepFronts(results, info.metric);
    writeSweepCsv(path(c, "sweep.csv"), results, fronts);
    writeSweepJson(path(c, "sweep.json"), results, fronts, info);
    writeSweepMarkdown(path(c, "sweep.md"), results, fronts, info);
    if (c.plot) drawPlot(c.outDir);
    const auto refused = std::count_if(results.begin(), results.end(), [](const SweepResult& r) { return !r.refused.empty(); });
    std::printf("%zu runs%s -> %s/sweep.csv, sweep.json, sweep.md%s\n", results.size(),
                refused ? (" (" + std::to_string(refused) + " refused: see sweep.md)").c_str() : "", c.outDir.c_str(),
                c.plot ? ", sweep.png" : "");
}

// --merge: DIR/runs/run-*.json, every run of one sweep, into the tables.
void mergeRuns(const SweepCommand& c) {
    std::vector<SweepRunFile> files;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(path(c, "runs"), ec))
        if (e.path().extension() == ".json") files.push_back(readSweepRunJson(e.path().string()));
    if (ec || files.empty()) throw Error("--merge: no run files in '" + path(c, "runs") + "' (weft sweep --run K writes them)");
    std::sort(files.begin(), files.end(), [](auto& a, auto& b) { return a.result.run.index < b.result.run.index; });
    std::vector<SweepResult> results;
    for (const SweepRunFile& f : files) {
        if (f.runCount != files.front().runCount || f.result.run.index != int(results.size()))
            throw Error("--merge: '" + path(c, "runs") + "' holds runs of different sweeps, or run " + std::to_string(results.size() + 1) +
                        " is missing");
        results.push_back(f.result);
    }
    if (int(results.size()) != files.front().runCount)
        throw Error("--merge: " + std::to_string(results.size()) + " of " + std::to_string(files.front().runCount) + " runs are done");
    writeReports(c, results, files.front().info);
}

void listRuns(const std::vector<SweepRun>& runs) {
    std::printf("%zu runs\n", runs.size());
    for (const SweepRun& r : runs) std::printf("%d %s %s\n", r.index + 1, r.technique.c_str(), runLabel(r).c_str());
}

void runSweepCommand(const SweepCommand& c) {
    if (c.merge) return mergeRuns(c);
    if (c.input.empty() || c.reference.empty()) throw Error("weft sweep needs a scene and --reference (or --merge -o DIR)");
    const TradeMetric metric = parseTradeMetric(c.metric);
    const RenderRequest base = c.renderOptions.request(c.input);
    tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, effectiveThreads(base.threads));
    const LoadedScene first = loadRequestScene(base);
    std::vector<SweepRun> runs = planSweep(base, c.groups, *first.scene);
    SweepReferences references(c.reference, path(c, "references"));
    references.check(runs, *first.scene);
    if (c.list) return listRuns(runs);
    if (c.only > int(runs.size())) throw Error("--run " + std::to_string(c.only) + ": the sweep has " + std::to_string(runs.size()) + " runs");
    createOutputFolder(c.outDir);  // only once every run has passed its checks
    const SweepReportInfo info{c.input, c.reference, metric, c.repeat};
    if (c.prepare) {
        prepareReferences(runs, base, first, references);
        return (void)std::printf("references of %zu runs ready in %s\n", runs.size(), path(c, "references").c_str());
    }
    const std::size_t count = runs.size();
    if (c.only > 0) runs = {runs[std::size_t(c.only - 1)]};
    const std::vector<SweepResult> results = runSweep(runs, base, first, references, {c.repeat, stderrIsTerminal()});
    if (c.only == 0) return writeReports(c, results, info);
    fs::create_directories(path(c, "runs"));
    char name[32];
    std::snprintf(name, sizeof name, "runs/run-%05d.json", c.only);
    writeSweepRunJson(path(c, name), {results.front(), int(count), info});
    std::printf("run %d of %zu -> %s\n", c.only, count, path(c, name).c_str());
}

const CommandRegistrar registrar{{"sweep", 40, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("sweep", "render every combination of --vary values and measure time, samples and error "
                                            "against a reference (CSV, JSON, Markdown, Pareto plot)");
    auto c = std::make_shared<SweepCommand>();
    cmd->add_option("input", c->input, "scene (.json), bare .vdb or builtin:NAME");
    // Triggered as parsed: a --vary belongs to the --technique before it.
    cmd->add_option_function<std::vector<std::string>>("--technique", [c](const std::vector<std::string>& v) {
        for (const std::string& t : v) c->groups.push_back(SweepGroup{t, {}});
    }, "technique of the --vary options after it (repeatable: one group per technique)")->allow_extra_args(false)->trigger_on_parse();
    cmd->add_option_function<std::vector<std::string>>("--vary", [c](const std::vector<std::string>& v) {
        for (const std::string& text : v) c->groups.back().axes.push_back(parseVary(text));
    }, "key=a,b,c: a technique parameter, or spp, seed or res (repeatable)")->allow_extra_args(false)->trigger_on_parse();
    cmd->add_option("--reference", c->reference, "reference image (.exr), or auto: each technique's converged render, cached in DIR");
    cmd->add_option("--repeat", c->repeat, "renders per setting; times are their median, min and max")->check(CLI::Range(1, 1000));
    cmd->add_option("--metric", c->metric, "error of the Pareto fronts: rmse, relmse, psnr, ssim, flip or maxabs");
    cmd->add_option("-o,--out", c->outDir, "output folder")->required();
    cmd->add_flag("!--no-plot", c->plot, "write the tables only");
    cmd->add_flag("--list", c->list, "print the runs, one a line, and render nothing (the size of a farm array)");
    cmd->add_flag("--prepare", c->prepare, "render the automatic references only (before a farm array starts)");
    cmd->add_option("--run", c->only, "render run K only, into DIR/runs/run-K.json (one farm task)")->check(CLI::PositiveNumber);
    cmd->add_flag("--merge", c->merge, "write the tables and the plot from DIR/runs/ (after the farm tasks)");
    c->renderOptions.install(*cmd);
    cmd->callback([c] { runSweepCommand(*c); });
}}};

}  // namespace

}  // namespace weft
