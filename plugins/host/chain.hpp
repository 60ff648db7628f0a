#pragma once
// Operations chained on one command line, as oiiotool chains them: each
// consumes the image the previous one left, e.g.
//   weft render builtin:cloud --res 256x256 exposure 1 preview c.png write c.exr
//   weft render shot.json --frames 1-8 atrous --set levels=4 colorconvert lin_rec709 acescg write out.#.exr
// The command line is read whole first (every step checks its arguments, and
// every file a step writes is checked before the first render); then each
// frame is rendered and passed through the steps in command-line order. A
// step's file names may carry a frame number (# or @), expanded per frame.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "core/image/io/image_io.hpp"
#include "plugins/host/render_job.hpp"

namespace weft {

struct ChainImage {
    Image image;
    Metadata metadata;         // from the render, written with the image
    ImageWindow window;        // a tile's place in its frame
    std::optional<int> frame;  // the frame rendered (names expand with it)
    std::vector<std::string> steps;  // operations applied since the render
};

struct ChainStep {
    std::string name;                  // as typed, for messages
    std::optional<std::string> writes; // the file it writes, frame-numbered or not
    std::function<void(ChainImage&)> apply;
};

// Records the render the steps act on (one per command line).
void setChainRender(std::vector<RenderRequest> renders);
// Adds a step; an Error naming it when no render comes before it.
void addChainStep(ChainStep step);
// Whether a render was recorded; runChain() renders it and applies the steps.
bool chainHasRender();
// Returns how many renders failed (each prints its error, the others go on).
int runChain();

// A step's file name for the image's frame.
std::string framePath(const std::string& name, const ChainImage& in);

}  // namespace weft
