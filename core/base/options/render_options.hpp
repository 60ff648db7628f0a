#pragma once
// The options of one render, declared once in renderOptions(): `weft render`
// generates its command-line options from the table, `weft batch` reads a
// job's keys through it and a scene file's "render" block reads its keys
// through it too, so a name, its range and its error text are the same
// everywhere, and `weft help options` prints the table.
//
// Precedence, in one place (effectiveRequest): an option given on the command
// line (or in a batch job, which is a command line written as JSON) wins over
// the scene's render block, which wins over the table's default. `set`
// values merge key by key, the command line's last.
#include <cstdint>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/base/options/params.hpp"

namespace weft {

class RenderMonitor;

struct RenderRequest {
    std::string input;            // scene .json, .vdb or builtin:NAME
    std::string output;           // .exr ("" in a chain: a later step writes)
    std::string preview;          // optional .png/.jpg
    std::string stats;            // optional .json
    std::string grid;             // grid of a bare .vdb input
    std::optional<std::string> technique;
    std::vector<std::string> sets;  // "key=value", later ones win
    std::optional<std::string> resolution;  // "WxH"
    std::optional<int> spp;
    std::optional<std::uint64_t> seed;
    int threads = 0;  // 0: all cores
    bool verbose = false;
    std::optional<std::string> frames;  // frame range to expand (requestsForFrames)
    std::optional<int> frame;  // the frame a scene file is loaded at (names already expanded)
    std::string tile;          // "i/n": render only row band i of n (core/base/options/frames.hpp); "" = all
    double maxMemoryGiB = 0;   // refuse renders whose images alone need more; 0 = 3/4 of physical memory
    RenderMonitor* monitor = nullptr;  // told the progress, polled for interrupts (core/base/run/render_monitor.hpp)
    std::string compression;   // the EXR's compression; "" = the default (core/base/options/exr_options.hpp)
    std::vector<std::string> pixelTypes;  // -d specs: half, float, CHANNEL=TYPE
};

// Where an option may be given.
enum RenderOptionPlace : unsigned { kOnCommandLine = 1, kInBatchJob = 2, kInScene = 4 };

struct RenderOption {
    ParamSpec spec;                    // name (the JSON key), type, default, range, doc
    std::string cli;                   // CLI11 names, e.g. "-o,--output"; a bare name is positional
    std::vector<std::string> aliases;  // other JSON keys accepted for it ("res", "params")
    unsigned places = kOnCommandLine | kInBatchJob;
    bool repeated = false;  // may be given many times (set)
    void (*store)(RenderRequest&, const std::string&) = nullptr;  // the checked value into the request
    // The label naming it in errors from `place`: "--spp", "spp" or "render.spp".
    std::string label(RenderOptionPlace place) const;
};

const std::vector<RenderOption>& renderOptions();
// By name or alias, among those allowed at `place`; nullptr if none.
const RenderOption* findRenderOption(std::string_view key, RenderOptionPlace place);
// The names allowed at `place`, comma separated (for unknown-key errors).
std::string renderOptionNames(RenderOptionPlace place);

// Checks one value against the option's type and range and stores it.
// Errors are one line naming the option as `label` and the value:
// "--spp 0 is outside [1, 1048576]", "render.spp 0 is outside [1, 1048576]".
void applyRenderOption(RenderRequest& r, const RenderOption& option, const std::string& text, const std::string& label);
// A JSON value (batch job or scene render block) as the texts a command line
// would give: numbers and booleans as written, [W, H] as "WxH", a set/params
// object as "key=value" each. Throws an Error (without a location) on other shapes.
std::vector<std::string> renderOptionTexts(const RenderOption& option, const nlohmann::json& value);
// Reads a whole JSON object (batch job or scene render block) into `r`;
// `fail(key, message)` reports a bad key or value and must throw.
void readRenderOptions(RenderRequest& r, const nlohmann::json& object, RenderOptionPlace place,
                       const std::function<void(const std::string&, const std::string&)>& fail);

// The request as rendered: `given` over the scene's render block over the
// table's defaults (technique, resolution, spp, seed and set).
RenderRequest effectiveRequest(const RenderRequest& given, const RenderRequest& scene);
// volume.raymarch, or volume.singlescatter for `set compat=vdb_render`
// (a vdb_render user's command line works as it is).
std::string defaultTechnique(const std::vector<std::string>& sets);

// Range checks for requests built in code rather than parsed (tests, chains).
void checkRenderNumber(std::string_view name, double value, RenderOptionPlace place);

// "WxH" -> (W, H), each in [1, 65536]; anything else is an error naming the text.
std::pair<int, int> parseResolution(const std::string& text);

// The table for `weft help options` and docs/usage.md.
std::string renderOptionsHelp();
std::string renderOptionsMarkdown();

}  // namespace weft
