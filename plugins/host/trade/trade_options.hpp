#pragma once
// The render options weft sweep and weft tune pass to every render they
// make (--res, --spp, --seed, --set, --threads, --grid), read through the
// render option table in command-line order, as weft render reads them.
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/base/options/render_options.hpp"

namespace weft {

struct TradeRenderOptions {
    std::vector<std::pair<const RenderOption*, std::string>> given;
    // Adds the options to `cmd`; this object must outlive the parse.
    void install(CLI::App& cmd);
    // `input` with the options applied, checked as a render checks them.
    RenderRequest request(const std::string& input) const;
};

}  // namespace weft
