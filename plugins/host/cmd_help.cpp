// weft help [NAME]: a technique's summary and parameter table, generated from
// the same table that validates its parameters.
#include <cstdio>

#include "plugins/host/command.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

void printHelp(const std::string& name) {
    if (name.empty()) {
        std::printf("techniques (weft help NAME for parameters):\n");
        for (const TechniqueInfo* t : techniques().all()) std::printf("  %-28s %s\n", t->name.c_str(), t->summary.c_str());
        return;
    }
    const TechniqueInfo& t = techniques().get(name);
    std::printf("%s: %s\n\nparameters (--set key=value):\n%s", t.name.c_str(), t.summary.c_str(), t.params.helpText().c_str());
}

const CommandRegistrar registrar{{"help", 90, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("help", "describe a technique and its parameters");
    auto name = std::make_shared<std::string>();
    cmd->add_option("name", *name, "technique name (omit to list them)");
    cmd->callback([name] { printHelp(*name); });
}}};

}  // namespace

}  // namespace weft
