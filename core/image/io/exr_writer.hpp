#pragma once
// Render outputs are written with OpenEXR itself: every render writes one,
// and OpenEXR starts in a moment where OpenImageIO (previews, reading any
// format: core/image/io/image_codec.hpp) would load some 260 libraries first.
#include <string>
#include <utility>
#include <vector>

#include "core/base/options/exr_options.hpp"
#include "core/image/image.hpp"

namespace weft {

// Writes the channels as `encoding` says (compression, half or float), with
// string attributes, the data window at (x, y) inside a fullWidth x
// fullHeight display window. No time stamp: same pixels, attributes and
// encoding, same bytes.
void writeExrFile(const std::string& path, const Image& image,
                  const std::vector<std::pair<std::string, std::string>>& attributes, int x, int y, int fullWidth,
                  int fullHeight, const ExrEncoding& encoding);

}  // namespace weft
