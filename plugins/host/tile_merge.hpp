#pragma once
// Assembling a frame from the tiles `weft render --tile i/n` wrote: every
// tile 1..n exactly once, all from the same render (same metadata apart from
// tile placement and counters), each band where tileRows() puts it.
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "core/image/io/image_io.hpp"

namespace weft {

struct MergedFrame {
    Image image;
    Metadata metadata;  // the tiles' shared metadata, counters summed, weft:complete last
};

// Reads and checks the tile files; an incomplete, duplicate or mismatched
// set is an Error naming the files and what differs.
MergedFrame mergeTiles(const std::vector<std::string>& tilePaths);

}  // namespace weft
