#pragma once
// How the command line spells the render options: the table
// (core/base/options/render_options.hpp) knows each by its JSON name, type,
// range and doc; here are CLI11's names for it, the label its errors give,
// and the table as `weft help options` prints it.
#include <string>
#include <string_view>

#include "core/base/options/render_options.hpp"

namespace weft {

// CLI11's names: "--NAME" (underscores as dashes) unless the option has
// names of its own ("-o,--output", "--res,--resolution"); a bare name is
// positional.
std::string commandLineNames(const RenderOption& option);
// The name errors give it: "--spp", "--output", or a positional's name.
std::string commandLineLabel(const RenderOption& option);

// Range checks for requests built in code rather than parsed (tests, chains,
// Python), with the command line's label: "--spp 0 is outside [1, 1048576]".
void checkRenderNumber(std::string_view name, double value);

// The table for `weft help options` and docs/usage.md.
std::string renderOptionsHelp();
std::string renderOptionsMarkdown();

}  // namespace weft
