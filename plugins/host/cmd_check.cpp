// weft check FRAME...: whether rendered frames are complete, for farm
// scripts. Prints "STATE<TAB>PATH" per file, STATE one of ok, missing,
// "corrupt: WHY"; a frame is ok when the whole image reads back and it
// carries weft:complete = 1 (written last into every finished render).
// Exit status 0 when all are ok, 2 otherwise.
#include <cstdio>
#include <filesystem>

#include "core/base/error.hpp"
#include "core/image/image_io.hpp"
#include "plugins/host/command.hpp"

namespace weft {

namespace {

std::string frameState(const std::string& path) {
    if (!std::filesystem::exists(path)) return "missing";
    Metadata md;
    try {
        readImage(path, &md);  // reads every pixel: a truncated file fails here
    } catch (const std::exception& e) {
        std::string why = e.what();
        for (char& c : why)
            if (c == '\n' || c == '\t') c = ' ';
        return "corrupt: " + why;
    }
    for (const auto& [k, v] : md)
        if (k == "weft:complete" && v == "1") return "ok";
    return "corrupt: no weft:complete attribute";
}

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
