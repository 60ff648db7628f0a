#pragma once
// Operations chained on one command line, as oiiotool chains them: each
// consumes the image the previous one left, e.g.
//   weft render builtin:cloud --res 256x256 exposure 1 preview c.png write c.exr
// The host runs the steps in command-line order.
#include <optional>
#include <string>
#include <vector>

#include "core/image.hpp"
#include "core/image_io.hpp"

namespace weft {

struct ChainImage {
    Image image;
    Metadata metadata;         // from the render, written with the image
    ImageWindow window;        // a tile's place in its frame
    std::vector<std::string> steps;  // operations applied since the render
};

struct ChainState {
    std::optional<ChainImage> current;
    bool wroteFile = false;  // some step (or the render itself) wrote a file
};

ChainState& chainState();

// The image a step consumes; an Error naming the step when nothing was rendered before it.
ChainImage& chainInput(const std::string& step);

}  // namespace weft
