// weft sweep SCENE [--technique T] --vary key=a,b,c [--vary ...] [--technique T2 --vary ...]
//            --reference REF.exr|auto [--repeat N] [--metric M] -o DIR
// Renders every combination in one process (the scene and its BVH loaded
// once), measures time, samples and the error against the reference, and
// writes DIR/sweep.csv, sweep.json, sweep.md and the Pareto plot sweep.png.
#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <thread>

#include "core/base/atomic_file.hpp"
#include "core/base/error.hpp"
#include "core/base/progress.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/trade/sweep_report.hpp"

namespace weft {

namespace {

namespace fs = std::filesystem;

struct SweepCommand {
    std::string input, outDir, reference, metric = "rmse";
    std::vector<std::pair<const RenderOption*, std::string>> renderOptions;  // --res, --spp, --seed, --set, --threads
    std::vector<SweepGroup> groups{SweepGroup{}};  // the first: --vary before any --technique
    int repeat = 1;
    bool plot = true;
};

RenderRequest baseRequest(const SweepCommand& c) {
    RenderRequest r;
    r.input = c.input;
    for (const auto& [option, text] : c.renderOptions) applyRenderOption(r, *option, text, option->label(kOnCommandLine));
    validateRequest(r);
    return r;
}

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

void runSweepCommand(const SweepCommand& c) {
    const TradeMetric metric = parseTradeMetric(c.metric);
    const RenderRequest base = baseRequest(c);
    const int threads = base.threads > 0 ? base.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, threads);
    const LoadedScene first = loadRequestScene(base);
    const std::vector<SweepRun> runs = planSweep(base, c.groups, *first.scene);
    SweepReferences references(c.reference, (fs::path(c.outDir) / "references").string());
    references.check(runs, *first.scene);
    createOutputFolder(c.outDir);  // only once every run has passed its checks
    const std::vector<SweepResult> results = runSweep(runs, base, first, references, {c.repeat, Progress::terminalAttached()});
    const SweepFronts fronts = sweepFronts(results, metric);
    const SweepReportInfo info{c.input, c.reference, metric, c.repeat};
    writeSweepCsv((fs::path(c.outDir) / "sweep.csv").string(), results, fronts);
    writeSweepJson((fs::path(c.outDir) / "sweep.json").string(), results, fronts, info);
    writeSweepMarkdown((fs::path(c.outDir) / "sweep.md").string(), results, fronts, info);
    if (c.plot) drawPlot(c.outDir);
    std::printf("%zu runs -> %s/sweep.csv, sweep.json, sweep.md%s\n", results.size(), c.outDir.c_str(), c.plot ? ", sweep.png" : "");
}

void addRenderOption(CLI::App& cmd, const std::shared_ptr<SweepCommand>& c, const char* name) {
    const RenderOption* o = findRenderOption(name, kOnCommandLine);
    auto store = [c, o](const std::vector<std::string>& values) {
        for (const std::string& v : values) c->renderOptions.emplace_back(o, v);
    };
    cmd.add_option_function<std::vector<std::string>>(o->cli, store, o->spec.doc)->allow_extra_args(false);
}

const CommandRegistrar registrar{{"sweep", 40, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("sweep", "render every combination of --vary values and measure time, samples and error "
                                            "against a reference (CSV, JSON, Markdown, Pareto plot)");
    auto c = std::make_shared<SweepCommand>();
    cmd->add_option("input", c->input, "scene (.json), bare .vdb or builtin:NAME")->required();
    // Triggered as parsed: a --vary belongs to the --technique before it.
    cmd->add_option_function<std::vector<std::string>>("--technique", [c](const std::vector<std::string>& v) {
        for (const std::string& t : v) c->groups.push_back(SweepGroup{t, {}});
    }, "technique of the --vary options after it (repeatable: one group per technique)")->allow_extra_args(false)->trigger_on_parse();
    cmd->add_option_function<std::vector<std::string>>("--vary", [c](const std::vector<std::string>& v) {
        for (const std::string& text : v) c->groups.back().axes.push_back(parseVary(text));
    }, "key=a,b,c: a technique parameter, or spp, seed or res (repeatable)")->allow_extra_args(false)->trigger_on_parse();
    cmd->add_option("--reference", c->reference, "reference image (.exr), or auto: each technique's converged render, cached in DIR")
        ->required();
    cmd->add_option("--repeat", c->repeat, "renders per setting; times are their median, min and max")->check(CLI::Range(1, 1000));
    cmd->add_option("--metric", c->metric, "error of the Pareto fronts: rmse, relmse, psnr, ssim, flip or maxabs");
    cmd->add_option("-o,--out", c->outDir, "output folder")->required();
    cmd->add_flag("!--no-plot", c->plot, "write the tables only");
    for (const char* name : {"resolution", "spp", "seed", "set", "threads", "grid"}) addRenderOption(*cmd, c, name);
    cmd->callback([c] { runSweepCommand(*c); });
}}};

}  // namespace

}  // namespace weft
