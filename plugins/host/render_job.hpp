#pragma once
// One render from the command line (or a pipeline) to files: load the scene,
// pick and validate the technique, render, and write EXR + preview + stats,
// each atomically. Every check that can fail on user input runs before the
// render starts, so bad input never costs render time or leaves files.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "core/image/image_io.hpp"
#include "core/base/render_context.hpp"

namespace weft {

struct RenderRequest {
    std::string input;            // scene .json, .vdb or builtin:NAME
    std::string output;           // .exr ("" in a chain: a later step writes)
    std::string preview;          // optional .png/.jpg
    std::string stats;            // optional .json
    std::string grid;             // grid of a bare .vdb input
    std::optional<std::string> technique;
    std::vector<std::string> sets;  // "key=value"
    std::optional<std::string> resolution;  // "WxH"
    std::optional<int> spp;
    std::optional<std::uint64_t> seed;
    int threads = 0;  // 0: all cores
    bool verbose = false;
    std::optional<int> frame;  // the frame a scene file is loaded at (names already expanded)
    std::string tile;          // "i/n": render only row band i of n (core/base/frames.hpp); "" = all
    double maxMemoryGiB = 0;   // refuse renders whose images alone need more; 0 = 3/4 of physical memory
};

struct RenderOutcome {
    Image image;          // the whole frame, or the tile's rows only
    ImageWindow window;   // where image lies in the frame
    Metadata metadata;  // what went into the EXR header
    CounterMap counters;
    std::vector<std::pair<std::string, double>> timingsMs;
};

// Checks what does not depend on the scene or the frame (resolution, tile,
// threads, outputs, and --set against the technique's table when the
// technique is known without loading the scene); throws on the first problem.
void validateRequest(const RenderRequest& request);

// Renders without writing anything (tests and chains use this directly).
RenderOutcome renderToImage(const RenderRequest& request);
// Renders and writes the requested files (the EXR only when output is set);
// returns what was rendered, for operations chained after it.
RenderOutcome runRender(const RenderRequest& request);

// One request per frame: names with a frame wildcard (input, output,
// preview, stats) expanded, frame set. Several frames need a wildcard in
// every output name, or they would overwrite each other: an Error says so.
std::vector<RenderRequest> requestsForFrames(const RenderRequest& request, const std::vector<int>& frames);

// Renders each request in turn, then hands its outcome to `after` (chained
// steps); a failing one prints its error (naming the frame) and the others
// go on. Returns how many failed.
using AfterRender = std::function<void(const RenderRequest&, RenderOutcome&)>;
int runRenders(const std::vector<RenderRequest>& requests, const AfterRender& after = {});

// "WxH" -> (W, H), each in [1, 65536]; anything else is an error naming the text.
std::pair<int, int> parseResolution(const std::string& text);

}  // namespace weft
