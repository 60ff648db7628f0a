// weft merge TILE... -o FRAME.exr: assembles the tiles of one frame written
// by `weft render --tile i/n` (see tile_merge.hpp), atomically. With
// --frame N, names with a frame number (# or @) are expanded first, so a
// farm task can name its frame's tiles by pattern.
#include <optional>

#include "core/base/files/atomic_file.hpp"
#include "core/base/options/frames.hpp"
#include "core/base/files/input_file.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/tile_merge.hpp"

namespace weft {

namespace {

struct MergeOptions {
    std::vector<std::string> tiles;
    std::string output;
    std::optional<int> frame;
};

void runMerge(MergeOptions o) {
    if (o.frame) {
        for (std::string& t : o.tiles) t = expandFrameName(t, *o.frame);
        o.output = expandFrameName(o.output, *o.frame);
    }
    for (const std::string& t : o.tiles) requireRegularFile(t, "image");  // known as inputs before the output is checked
    checkOutputPath(o.output, "output");
    const MergedFrame frame = mergeTiles(o.tiles);
    writeExr(frame.image, o.output, frame.metadata);
}

const CommandRegistrar registrar{{"merge", 15, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("merge", "assemble the tiles of a frame (render --tile i/n) into one EXR");
    auto o = std::make_shared<MergeOptions>();
    cmd->add_option("tiles", o->tiles, "tile EXRs, all n of one frame, in any order")->required();
    cmd->add_option("-o,--output", o->output, "merged frame .exr")->required();
    cmd->add_option("--frame", o->frame, "frame number for names with # or @");
    cmd->callback([o] { runMerge(*o); });
}}};

}  // namespace

}  // namespace weft
