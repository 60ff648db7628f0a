// weft render INPUT -o OUT.exr [options]: one frame of a scene.
#include "plugins/command.hpp"
#include "plugins/render_job.hpp"

namespace weft {

namespace {

const CommandRegistrar registrar{{"render", 10, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("render", "render a scene (.json), a bare .vdb or builtin:NAME to an EXR");
    auto r = std::make_shared<RenderRequest>();
    cmd->add_option("input", r->input, "scene .json, .vdb file, or builtin:cloud|builtin:sphere")->required();
    cmd->add_option("-o,--output", r->output, "output EXR (RGBA + AOVs + metadata)")->required();
    cmd->add_option("--preview", r->preview, "also write a display-referred PNG/JPEG through OpenColorIO");
    cmd->add_option("--stats", r->stats, "write counters, timings and parameters as JSON");
    cmd->add_option("--grid", r->grid, "grid to render from a bare .vdb (default: density, else the first float grid)");
    cmd->add_option("--technique", r->technique, "technique name (weft --list-plugins)");
    cmd->add_option("--set", r->sets, "technique parameter key=value (weft help TECHNIQUE)")->allow_extra_args(false);
    cmd->add_option("--res", r->resolution, "image size WxH (default: the scene's, else 512x512)");
    cmd->add_option("--spp", r->spp, "camera samples per pixel");
    cmd->add_option("--seed", r->seed, "random seed (same seed, same image)");
    cmd->add_option("--threads", r->threads, "worker threads, 0 = all cores");
    cmd->add_flag("-v,--verbose", r->verbose, "print the counter table and timings");
    cmd->callback([r] { runRender(*r); });
}}};

}  // namespace

}  // namespace weft
