// weft hwsim REPLAY --profile P [--set key=value ...] [--stats S.json] [-o image.exr]
// Runs a paper's pass structure through the modelled fragment pipeline and
// prints a counter table (counters as rows, compared variants as columns).
// `weft hwsim --list-profiles` and `--list-replays` list what is built in;
// `weft hwsim REPLAY --params` prints the replay's parameter table.
#include <cstdio>
#include <map>

#include "core/base/files/atomic_file.hpp"
#include "core/base/error.hpp"
#include "core/image/io/image_io.hpp"
#include "hwsim/replay.hpp"
#include "plugins/host/command.hpp"

namespace weft {

namespace {

struct HwsimOptions {
    std::string replay;
    std::string profile = "ideal";
    std::vector<std::string> sets;
    std::string stats, image;
    bool listProfiles = false, listReplays = false, params = false;
};

void listProfiles() {
    for (const hwsim::Profile& p : hwsim::builtinProfiles()) std::printf("%-16s %s\n", p.name.c_str(), p.description.c_str());
}

void listReplays() {
    for (const hwsim::ReplayInfo* r : hwsim::replays().all()) std::printf("%-16s %s\n", r->name.c_str(), r->summary.c_str());
}

void runHwsim(const HwsimOptions& o) {
    if (o.listProfiles) return listProfiles();
    if (o.listReplays) return listReplays();
    if (o.replay.empty()) throw Error("hwsim: name a replay (weft hwsim --list-replays)");
    const hwsim::ReplayInfo& info = hwsim::replays().get(o.replay);
    if (o.params) {
        std::printf("%s: %s\n\nparameters (--set key=value):\n%s", info.name.c_str(), info.summary.c_str(),
                    info.params.helpText().c_str());
        return;
    }
    const hwsim::Profile& profile = hwsim::findProfile(o.profile);
    std::map<std::string, std::string> given;
    for (const std::string& s : o.sets) given.insert(splitKeyValue(s, "--set"));
    const ParamSet params = info.params.parse(given);
    if (!o.stats.empty()) checkOutputPath(o.stats, "--stats");
    if (!o.image.empty()) checkOutputPath(o.image, "-o");
    const hwsim::ReplayResult result = info.run(profile, params);
    std::printf("%s under %s\n%s", info.name.c_str(), profile.name.c_str(), hwsim::replayTable(result).c_str());
    std::printf("\n%s", hwsim::replayPredictions(result, profile).c_str());
    if (!o.stats.empty()) writeTextAtomically(o.stats, hwsim::replayStatsJson(info.name, profile, params, result), "stats");
    if (!o.image.empty()) {
        if (!result.image) throw Error("hwsim: replay '" + info.name + "' makes no image (-o)");
        writeExr(*result.image, o.image, {{"weft:hwsim:replay", info.name}, {"weft:hwsim:profile", profile.name}});
    }
}

const CommandRegistrar registrar{{"hwsim", 40, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("hwsim", "replay a paper's GPU passes through the modelled fragment pipeline and count per stage");
    auto o = std::make_shared<HwsimOptions>();
    cmd->add_option("replay", o->replay, "replay name (--list-replays)");
    cmd->add_option("--profile", o->profile, "hardware profile name or .json file (--list-profiles)");
    cmd->add_option("--set", o->sets, "replay parameter key=value (repeatable; --params lists them)");
    cmd->add_option("--stats", o->stats, "write the counters as JSON");
    cmd->add_option("-o,--output", o->image, "write the replay's image (replays of a renderer)");
    cmd->add_flag("--list-profiles", o->listProfiles, "list the hardware profiles");
    cmd->add_flag("--list-replays", o->listReplays, "list the replays");
    cmd->add_flag("--params", o->params, "print the replay's parameters");
    cmd->callback([o] { runHwsim(*o); });
}}};

}  // namespace

}  // namespace weft
