// weft help [NAME] [--markdown]: a technique's summary and parameter table,
// generated from the same table that validates its parameters. --markdown
// prints the section docs/techniques/NAME.md holds between its
// "<!-- BEGIN weft help NAME --markdown -->" and "<!-- END ... -->" lines
// (scripts/gen-docs.sh writes it there; tests/cli/docs_test.cpp checks it).
#include <cstdio>
#include <memory>
#include <string>

#include "core/base/run/counters.hpp"
#include "core/base/error.hpp"
#include "core/base/options/render_options.hpp"

#include "plugins/host/command.hpp"
#include "plugins/host/help_text.hpp"
#include "plugins/host/render_cli.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

void printList() {
    std::printf("weft help options: the render options (command line, batch jobs, scene render block)\n");
    std::printf("weft help counters: the counters a render records\n");
    std::printf("techniques (weft help NAME for parameters):\n");
    for (const TechniqueInfo* t : techniques().all()) std::printf("  %-28s %s\n", t->name.c_str(), t->summary.c_str());
}

// What weft sweep and weft tune use: the converged reference and the knobs.
std::string referenceText(const TechniqueInfo& t) {
    if (t.reference.technique.empty()) return "none";
    std::string text = t.reference.technique;
    for (const std::string& kv : t.reference.sets) text += " " + kv;
    return text + " spp=" + std::to_string(t.reference.spp);
}

std::string knobsText(const TechniqueInfo& t) {
    std::string text;
    for (const TradeKnob& k : t.knobs) {
        text += (text.empty() ? "" : "; ") + k.key + " ";
        for (std::size_t i = 0; i < k.values.size(); ++i) text += (i ? "," : "") + k.values[i];
    }
    return text.empty() ? "none" : text;
}

void printText(const TechniqueInfo& t) { std::printf("%s", techniqueHelpText(t).c_str()); }

void printMarkdown(const TechniqueInfo& t) {
    const bool stop = !t.summary.empty() && t.summary.back() == '.';
    std::printf("## Parameters of `%s`\n\n%s%s\n\n", t.name.c_str(), t.summary.c_str(), stop ? "" : ".");
    std::printf("Set with `--set key=value` or in a scene file's `render.params`; `weft help %s` prints the same.\n\n",
                t.name.c_str());
    std::printf("%s", t.params.markdownTable().c_str());
    std::printf("\nConverged reference (`weft sweep`/`weft tune --reference auto`): `%s`.\n"
                "Speed/accuracy knobs searched by `weft tune`, cheapest first: `%s`.\n",
                referenceText(t).c_str(), knobsText(t).c_str());
}

struct HelpOptions {
    std::string name;
    bool markdown = false;
};

// `weft help options`: the one table every way of asking for a render reads.
void printRenderOptions(bool markdown) {
    if (markdown) return void(std::printf("%s", renderOptionsMarkdown().c_str()));
    std::printf("render options: name (JSON key), type, default, allowed, meaning; then where it may be given\n"
                "(precedence: command line or batch job > scene \"render\" block > default):\n%s",
                renderOptionsHelp().c_str());
}

// `weft help counters`: every declared counter (core/base/run/counters.hpp).
void printCounters(bool markdown) {
    if (markdown) return void(std::printf("%s", declaredCountersMarkdown().c_str()));
    std::printf("counters (stats JSON \"counters\", EXR weft:counter:NAME):\n");
    for (const auto& [name, doc] : declaredCounters()) std::printf("  %-28s %s\n", name.c_str(), doc.c_str());
}

void printHelp(const HelpOptions& o) {
    if (o.name == "options") return printRenderOptions(o.markdown);
    if (o.name == "counters") return printCounters(o.markdown);
    if (o.name.empty()) {
        if (o.markdown) throw Error("weft help --markdown needs a technique name (weft help lists them)");
        return printList();
    }
    const TechniqueInfo& t = techniques().get(o.name);
    o.markdown ? printMarkdown(t) : printText(t);
}

const CommandRegistrar registrar{{"help", 90, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("help", "describe a technique and its parameters, or the render options (weft help options)");
    auto o = std::make_shared<HelpOptions>();
    cmd->add_option("name", o->name, "technique name, options or counters (omit to list them)");
    cmd->add_flag("--markdown", o->markdown, "print the parameter section of docs/techniques/NAME.md");
    cmd->callback([o] { printHelp(*o); });
}}};

}  // namespace

std::string techniqueHelpText(const TechniqueInfo& t) {
    return t.name + ": " + t.summary + "\n\nparameters (--set key=value):\n" + t.params.helpText() +
           "\nconverged reference (sweep/tune --reference auto): " + referenceText(t) +
           "\nspeed/accuracy knobs (weft tune), cheapest first: " + knobsText(t) + "\n";
}

}  // namespace weft
