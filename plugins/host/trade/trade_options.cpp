#include "plugins/host/trade/trade_options.hpp"

#include "plugins/host/render_cli.hpp"
#include "plugins/host/render_job.hpp"

namespace weft {

void TradeRenderOptions::install(CLI::App& cmd) {
    for (const char* name : {"resolution", "spp", "seed", "set", "threads", "grid"}) {
        const RenderOption* o = findRenderOption(name, kOnCommandLine);
        cmd.add_option_function<std::vector<std::string>>(commandLineNames(*o), [this, o](const std::vector<std::string>& values) {
            for (const std::string& v : values) given.emplace_back(o, v);
        }, o->spec.doc)->allow_extra_args(false);
    }
}

RenderRequest TradeRenderOptions::request(const std::string& input) const {
    RenderRequest r;
    r.input = input;
    for (const auto& [option, text] : given) applyRenderOption(r, *option, text, commandLineLabel(*option));
    validateRequest(r);
    return r;
}

}  // namespace weft
