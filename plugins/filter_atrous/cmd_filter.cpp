// weft filter atrous IN.exr -o OUT.exr [--set key=value]...: the
// edge-avoiding A-Trous filter (core/screen/atrous.hpp) applied to one RGB layer of
// an EXR, guided by the normal and position layers stored beside it. Every
// other channel and the input's metadata are kept; the filter's parameters
// are added as weft:filter:atrous:<key>.
// As a chain step after a render (plugins/host/chain.hpp):
//   weft render scene.json atrous --set layer=indirect write out.exr
#include <chrono>
#include <cstdio>
#include <map>

#include "core/base/files/atomic_file.hpp"
#include "core/base/files/input_file.hpp"
#include "core/base/error.hpp"
#include "core/image/io/image_io.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/chain.hpp"
#include "plugins/filter_atrous/atrous_params.hpp"

namespace weft {

namespace {

const ParamTable& filterTable() {
    static const ParamTable table("filter atrous", [] {
        std::vector<ParamSpec> specs = atrousParamSpecs();
        specs.push_back(stringParam("layer", "", "RGB layer to filter: '' = R,G,B; 'indirect' = indirect.R/G/B"));
        specs.push_back(stringParam("normal", "N", "normal layer (its .X/.Y/.Z channels; zero = background)"));
        specs.push_back(stringParam("position", "P", "world position layer (its .X/.Y/.Z channels)"));
        specs.push_back(stringParam("weights", "", "channel that weights every tap, e.g. sampleCount (a pixel's sample count); '' = none"));
        return specs;
    }());
    return table;
}

struct FilterOptions {
    std::string input, output, preview;
    std::vector<std::string> sets;
    bool verbose = false;
};

ParamSet parseSets(const std::vector<std::string>& sets) {
    std::map<std::string, std::string> given;
    for (const std::string& kv : sets) {
        auto [k, v] = splitKeyValue(kv, "--set");
        given[k] = v;
    }
    return filterTable().parse(given);
}

void filterImage(Image& image, const ParamSet& params, const AtrousSettings& settings) {
    atrousFilterImage(image, params.getString("layer"), params.getString("normal"), params.getString("position"), settings,
                      params.getString("weights"));
}

void runFilter(const FilterOptions& o) {
    const ParamSet params = parseSets(o.sets);
    const AtrousSettings settings = atrousSettingsFrom(params);
    requireRegularFile(o.input, "image");  // known as an input before the outputs are checked
    checkOutputPath(o.output, "output");
    if (!o.preview.empty()) checkOutputPath(o.preview, "preview");
    Metadata metadata;
    Image image = readImage(o.input, &metadata);
    const auto start = std::chrono::steady_clock::now();
    try {
        filterImage(image, params, settings);
    } catch (const Error& e) {
        throw Error("'" + o.input + "': " + e.what());
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    for (const auto& [k, v] : params.values()) metadata.emplace_back("weft:filter:atrous:" + k, v);
    writeExr(image, o.output, metadata);
    if (!o.preview.empty()) writePreview(image, o.preview);
    if (o.verbose) std::printf("atrous: %dx%d, %d levels, %.1f ms\n", image.width(), image.height(), settings.levels, ms);
}

const CommandRegistrar registrar{{"filter", 40, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("filter", "image filters over an EXR and its AOV layers");
    cmd->require_subcommand(1);
    auto* atrous = cmd->add_subcommand("atrous", "edge-avoiding A-Trous wavelet filter guided by the N and P layers");
    atrous->footer("parameters (--set key=value):\n" + filterTable().helpText());
    auto o = std::make_shared<FilterOptions>();
    atrous->add_option("input", o->input, "EXR with the layer to filter and its guide layers")->required();
    atrous->add_option("-o,--output", o->output, "output EXR (written atomically)")->required();
    atrous->add_option("--preview", o->preview, "also write a display-referred PNG/JPEG");
    atrous->add_option("--set", o->sets, "filter parameter key=value")->allow_extra_args(false);
    atrous->add_flag("-v,--verbose", o->verbose, "print the filter time");
    atrous->callback([o] { runFilter(*o); });
}}};

// The chain step: the same filter on the previous result.
void addAtrousStep(const std::vector<std::string>& sets) {
    const ParamSet params = parseSets(sets);
    const AtrousSettings settings = atrousSettingsFrom(params);
    std::string text = "atrous";
    for (const std::string& kv : sets) text += " " + kv;
    addChainStep({"atrous", std::nullopt, [params, settings, text](ChainImage& in) {
        filterImage(in.image, params, settings);
        for (const auto& [k, v] : params.values()) in.metadata.emplace_back("weft:filter:atrous:" + k, v);
        in.steps.push_back(text);
    }});
}

const CommandRegistrar atrousStep{{"atrous", 44, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("atrous", "chain step: A-Trous filter the previous result (parameters as `weft filter atrous`)");
    auto sets = std::make_shared<std::vector<std::string>>();
    cmd->add_option("--set", *sets, "filter parameter key=value")->allow_extra_args(false);
    cmd->callback([sets] { addAtrousStep(*sets); });
    cmd->immediate_callback();
}}};

}  // namespace

}  // namespace weft
