#pragma once
// The options of one render, declared once in renderOptions(): `weft render`
// generates its command-line options from the table (spelt by the host:
// plugins/host/render_cli.hpp), `weft batch` reads a
// job's keys through it and a scene file's "render" block reads its keys
// through it too, so a name, its range and its error text are the same
// everywhere, and `weft help options` prints the table.
//
// Precedence, in one place (effectiveRender): an option given on the command
// line (or in a batch job, which is a command line written as JSON) wins over
// the scene's render block, which wins over the table's default. `set`
// values merge key by key, the command line's last.
#include <cstdint>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/options/frames.hpp"
#include "core/base/options/params.hpp"
#include "core/base/options/scene_render.hpp"

namespace weft {

class RenderMonitor;

// A render as asked for, every value checked when it was read: what a scene
// may say too (technique, set, resolution, spp, seed: SceneRender), then
// what only a command line or batch job may say.
struct RenderRequest : SceneRender {
    std::string input;            // scene .json, .vdb or builtin:NAME
    std::string output;           // .exr ("" in a chain: a later step writes)
    std::string preview;          // optional .png/.jpg
    std::string stats;            // optional .json
    std::string grid;             // grid of a bare .vdb input
    int threads = 0;  // 0: all cores
    bool verbose = false;
    std::optional<std::vector<int>> frames;  // frames to expand (requestsForFrames)
    std::optional<int> frame;  // the frame a scene file is loaded at (names already expanded)
    std::optional<TileSpec> tile;  // render only this row band (core/base/options/frames.hpp); none = all
    double maxMemoryGiB = 0;   // refuse renders whose images alone need more; 0 = 3/4 of physical memory
    RenderMonitor* monitor = nullptr;  // told the progress, polled for interrupts (core/base/run/render_monitor.hpp)
    std::string compression;   // the EXR's compression; "" = the default (core/base/options/exr_options.hpp)
    std::vector<std::string> pixelTypes;  // -d specs: half, float, CHANNEL=TYPE
};

// What renders once the command line, the scene and the table's defaults
// are merged: every value is there.
struct EffectiveRender {
    std::string technique;
    std::vector<std::string> sets;  // the scene's, then the command line's
    Resolution resolution;
    int spp = 1;
    std::uint64_t seed = 0;
};

// Where an option may be given.
enum RenderOptionPlace : unsigned { kOnCommandLine = 1, kInBatchJob = 2, kInScene = 4 };

struct RenderOption {
    ParamSpec spec;                    // name (the JSON key), type, default, range, doc
    std::vector<std::string> aliases;  // other JSON keys accepted for it ("res", "params")
    unsigned places = kOnCommandLine | kInBatchJob;
    bool repeated = false;  // may be given many times (set)
    // The checked value into what it belongs to: one of the two is set,
    // storeInScene for the options a scene may give.
    void (*store)(RenderRequest&, const std::string&) = nullptr;
    void (*storeInScene)(SceneRender&, const std::string&) = nullptr;
    // The label naming it in errors from a batch job ("spp") or a scene
    // ("render.spp"); the command line's labels are the host's.
    std::string label(RenderOptionPlace place) const;
};

const std::vector<RenderOption>& renderOptions();
// By name or alias, among those allowed at `place`; nullptr if none.
const RenderOption* findRenderOption(std::string_view key, RenderOptionPlace place);
// The names allowed at `place`, comma separated (for unknown-key errors).
std::string renderOptionNames(RenderOptionPlace place);

// Checks one value against the option's type and range and stores it.
// Errors are one line naming the option as `label` and the value:
// "spp 0 is outside [1, 1048576]", "render.spp 0 is outside [1, 1048576]".
void applyRenderOption(RenderRequest& r, const RenderOption& option, const std::string& text, const std::string& label);
// The same for an option a scene may give (places has kInScene).
void applyRenderOption(SceneRender& r, const RenderOption& option, const std::string& text, const std::string& label);
// A JSON value (batch job or scene render block) as the texts a command line
// would give: numbers and booleans as written, [W, H] as "WxH", a set/params
// object as "key=value" each. Throws an Error (without a location) on other shapes.
std::vector<std::string> renderOptionTexts(const RenderOption& option, const nlohmann::json& value);
// Reads a whole JSON object into `r`: a batch job, or a scene's render block;
// `fail(key, message)` reports a bad key or value and must throw.
using RenderOptionFailure = std::function<void(const std::string&, const std::string&)>;
void readRenderOptions(RenderRequest& r, const nlohmann::json& job, const RenderOptionFailure& fail);
void readSceneRender(SceneRender& r, const nlohmann::json& block, const RenderOptionFailure& fail);

// The render as it runs: `given` over the scene's render block over the
// table's defaults (technique, resolution, spp, seed and set).
EffectiveRender effectiveRender(const SceneRender& given, const SceneRender& scene);
// volume.raymarch, or volume.singlescatter for `set compat=vdb_render`
// (a vdb_render user's command line works as it is).
std::string defaultTechnique(const std::vector<std::string>& sets);

}  // namespace weft
