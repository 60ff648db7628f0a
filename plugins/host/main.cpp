// weft: the command-line host. Sub-commands register themselves (see
// plugins/host/command.hpp); errors become one line on stderr and exit status 1.
#include <openvdb/Exceptions.h>

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "plugins/host/command.hpp"
#include "plugins/host/chain.hpp"
#include "plugins/host/command_line_monitor.hpp"
#include "plugins/plugin_api.hpp"

namespace {

void listPlugins() {
    for (const weft::TechniqueInfo* t : weft::techniques().all())
        std::printf("%-28s %s\n", t->name.c_str(), t->summary.c_str());
}

int run(int argc, char** argv) {
    CLI::App app{"weft: offline renderer of OpenVDB volumes and meshes with sampling techniques from the literature"};
    app.set_version_flag("--version", std::string("weft ") + WEFT_VERSION);
    app.require_subcommand(0, 0);  // any number: steps chain (plugins/host/chain.hpp)
    bool list = false;
    app.add_flag("--list-plugins", list, "list the registered techniques, one per line");
    weft::loadExternalPlugins();
    auto cmds = weft::commands().all();
    std::sort(cmds.begin(), cmds.end(), [](auto* a, auto* b) { return a->order < b->order; });
    for (const weft::CommandInfo* c : cmds) c->install(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::fprintf(stderr, "weft: error: %s\n", e.what());
        return 1;
    }
    if (list) listPlugins();
    else if (app.get_subcommands().empty()) std::cout << app.help();
    else if (weft::chainHasRender() && weft::runChain() > 0)
        return 1;
    return weft::commandExitStatus();
}

}  // namespace

int main(int argc, char** argv) {
    weft::installStopSignalHandlers();
    try {
        return run(argc, argv);
    } catch (const weft::Cancelled& e) {
        weft::endBySignalIfReceived();  // SIGINT/SIGTERM stopped a render: end as the signal would
        std::fprintf(stderr, "weft: error: %s\n", e.what());
    } catch (const weft::Error& e) {
        std::fprintf(stderr, "weft: error: %s\n", weft::printableLine(e.what()).c_str());
    } catch (const openvdb::Exception& e) {
        std::fprintf(stderr, "weft: error: OpenVDB: %s\n", weft::printableLine(e.what()).c_str());
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "weft: error: out of memory (try a smaller --res, fewer samples or a coarser grid)\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "weft: error: %s\n", weft::printableLine(e.what()).c_str());
    }
    return 1;
}
