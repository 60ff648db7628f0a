#pragma once
// Sub-commands of the `weft` host (render, diff, help, ...). Each lives in
// its own file and registers itself; a technique folder may add one too.
#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "core/base/registry.hpp"

namespace weft {

struct CommandInfo {
    std::string name;
    int order;  // position in `weft --help`
    std::function<void(CLI::App& app)> install;  // adds the subcommand and its callback
};

using CommandRegistry = NamedRegistry<CommandInfo>;
CommandRegistry& commands();

struct CommandRegistrar {
    explicit CommandRegistrar(CommandInfo info) { commands().add(std::move(info)); }
};

// Exit status the running command asks for (diff --fail sets 2).
int& commandExitStatus();

// "key=value" -> (key, value); a missing '=' or empty key is an error naming the text.
std::pair<std::string, std::string> splitKeyValue(const std::string& text, const std::string& option);

}  // namespace weft
