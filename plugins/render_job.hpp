#pragma once
// One render from the command line (or a pipeline) to files: load the scene,
// pick and validate the technique, render, and write EXR + preview + stats,
// each atomically. Every check that can fail on user input runs before the
// render starts, so bad input never costs render time or leaves files.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/image.hpp"
#include "core/image_io.hpp"
#include "core/render_context.hpp"

namespace weft {

struct RenderRequest {
    std::string input;            // scene .json, .vdb or builtin:NAME
    std::string output;           // .exr
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
};

struct RenderOutcome {
    Image image;
    Metadata metadata;  // what went into the EXR header
    CounterMap counters;
    std::vector<std::pair<std::string, double>> timingsMs;
};

// Renders without writing anything (tests and chains use this directly).
RenderOutcome renderToImage(const RenderRequest& request);
// Renders and writes the requested files.
void runRender(const RenderRequest& request);

// "WxH" -> (W, H), each in [1, 65536]; anything else is an error naming the text.
std::pair<int, int> parseResolution(const std::string& text);

}  // namespace weft
