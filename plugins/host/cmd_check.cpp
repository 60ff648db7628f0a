// weft check FRAME...: whether rendered frames are complete, for farm
// scripts. Prints "STATE<TAB>PATH" per file, STATE as frameState
// (frame_check.hpp) says: ok, missing or "corrupt: WHY".
// Exit status 0 when all are ok, 2 otherwise.
#include <cstdio>

#include "plugins/host/command.hpp"
#include "plugins/host/frame_check.hpp"

namespace weft {

namespace {

const CommandRegistrar registrar{{"check", 17, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("check", "report whether rendered frames are complete (ok / missing / corrupt)");
    auto paths = std::make_shared<std::vector<std::string>>();
    cmd->add_option("frames", *paths, "EXR files to check")->required();
    cmd->callback([paths] {
        for (const std::string& p : *paths) {
            const std::string state = frameState(p);
            std::printf("%s\t%s\n", state.c_str(), p.c_str());
            if (state != "ok") commandExitStatus() = 2;
        }
        std::fflush(stdout);
    });
}}};

}  // namespace

}  // namespace weft
