// weft render INPUT -o OUT.exr [options]: one frame, a frame range
// (--frames, names with # or @) or one tile of a frame (--tile i/n).
// Without -o the image goes to chained steps (see chain.hpp).
#include <memory>
#include <vector>

#include "core/base/error.hpp"
#include "core/base/options/frames.hpp"
#include "core/base/options/render_options.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/chain.hpp"
#include "plugins/host/render_cli.hpp"
#include "plugins/host/render_job.hpp"

namespace weft {

namespace {

// Values in command-line order; parsed through the table once CLI11 is done.
struct RenderCommand {
    std::vector<std::pair<const RenderOption*, std::string>> given;
    RenderRequest request() const {
        RenderRequest r;
        for (const auto& [option, text] : given) applyRenderOption(r, *option, text, commandLineLabel(*option));
        return r;
    }
};

// Checks what every frame shares once, so a bad option fails at once
// instead of once per frame.
std::vector<RenderRequest> requestsOf(const RenderCommand& c) {
    const RenderRequest r = c.request();
    validateRequest(r);
    if (!r.frames) return {r};
    return requestsForFrames(r, *r.frames);
}

// One CLI11 option per row of the render option table.
void addOption(CLI::App& cmd, const std::shared_ptr<RenderCommand>& c, const RenderOption& o) {
    const RenderOption* p = &o;
    const std::string names = commandLineNames(o);
    const std::string doc = o.spec.doc + (o.spec.defaultValue.empty() ? "" : " (default " + o.spec.defaultValue + ")");
    if (o.spec.type == ParamType::Bool) {
        cmd.add_flag_function(names, [c, p](std::int64_t) { c->given.emplace_back(p, "true"); }, doc);
        return;
    }
    if (o.repeated) {
        cmd.add_option_function<std::vector<std::string>>(names, [c, p](const std::vector<std::string>& values) {
            for (const std::string& v : values) c->given.emplace_back(p, v);
        }, doc)->allow_extra_args(false);
        return;
    }
    auto* option = cmd.add_option_function<std::string>(names, [c, p](const std::string& v) { c->given.emplace_back(p, v); }, doc);
    if (o.spec.name == "input") option->required();
}

const CommandRegistrar registrar{{"render", 10, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("render", "render a scene (.json), a bare .vdb or builtin:NAME to an EXR (weft help options: the options)");
    auto c = std::make_shared<RenderCommand>();
    for (const RenderOption& o : renderOptions())
        if (o.places & kOnCommandLine) addOption(*cmd, c, o);
    cmd->callback([c] { setChainRender(requestsOf(*c)); });
    cmd->immediate_callback();  // steps after it on the command line attach to it
}}};

}  // namespace

}  // namespace weft
