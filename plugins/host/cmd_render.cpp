// weft render INPUT -o OUT.exr [options]: one frame, a frame range
// (--frames, names with # or @) or one tile of a frame (--tile i/n).
// Without -o the image goes to chained steps (see chain.hpp).
#include <optional>

#include "core/base/error.hpp"
#include "core/base/frames.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/chain.hpp"
#include "plugins/host/render_job.hpp"

namespace weft {

namespace {

struct RenderCommand {
    RenderRequest request;
    std::optional<std::string> frames;
};

// Checks what every frame shares once, so a bad option fails at once
// instead of once per frame.
std::vector<RenderRequest> requestsOf(const RenderCommand& c) {
    validateRequest(c.request);
    if (!c.frames) return {c.request};
    if (c.frames->find_first_not_of(" \t") == std::string::npos)
        throw Error("--frames is empty: give frames such as 1001-1100, 1,3,5-9 or 7");
    return requestsForFrames(c.request, parseFrameRange(*c.frames));
}

const CommandRegistrar registrar{{"render", 10, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("render", "render a scene (.json), a bare .vdb or builtin:NAME to an EXR");
    auto c = std::make_shared<RenderCommand>();
    RenderRequest* r = &c->request;
    cmd->add_option("input", r->input, "scene .json, .vdb file, or builtin:cloud|builtin:sphere; # or @ = frame number")->required();
    cmd->add_option("-o,--output", r->output, "output EXR (RGBA + AOVs + metadata); # or @ = frame number");
    cmd->add_option("--frames", c->frames, "frames to render, e.g. 1001-1100x2, 1,3,5-9, -5--1");
    cmd->add_option("--tile", r->tile, "render only tile i of n (1-based horizontal bands), e.g. 2/4; merge with `weft merge`");
    cmd->add_option("--preview", r->preview, "also write a display-referred PNG/JPEG through OpenColorIO");
    cmd->add_option("--stats", r->stats, "write counters, timings and parameters as JSON");
    cmd->add_option("--grid", r->grid, "grid to render from a bare .vdb (default: density, else the first float grid)");
    cmd->add_option("--technique", r->technique, "technique name (weft --list-plugins)");
    cmd->add_option("--set", r->sets, "technique parameter key=value (weft help TECHNIQUE)")->allow_extra_args(false);
    cmd->add_option("--res", r->resolution, "image size WxH (default: the scene's, else 512x512)");
    cmd->add_option("--spp", r->spp, "camera samples per pixel");
    cmd->add_option("--seed", r->seed, "random seed (same seed, same image)");
    cmd->add_option("--threads", r->threads, "worker threads, 0 = all cores");
    cmd->add_option("--max-memory", r->maxMemoryGiB, "refuse renders whose images need more than this many GiB (0 = 3/4 of physical memory)");
    cmd->add_flag("-v,--verbose", r->verbose, "print the counter table and timings");
    cmd->callback([c] { setChainRender(requestsOf(*c)); });
    cmd->immediate_callback();  // steps after it on the command line attach to it
}}};

}  // namespace

}  // namespace weft
