#pragma once
// PNG previews are written with libpng itself: a preview is what a farm
// frame or a pipeline step writes beside every EXR, and OpenImageIO, which
// reads and writes the other preview formats (core/image/io/image_codec.hpp),
// costs a process a third of a second to load (it links some 260 shared
// libraries). libpng starts in a moment.
#include <string>

namespace weft {

// Writes width x height 8-bit RGB pixels (row by row, no padding), sRGB
// encoded, as a PNG with an sRGB chunk; returns "" or what went wrong. No
// time stamp: same pixels, same bytes.
std::string writePngRgb8(const std::string& path, int width, int height, const unsigned char* rgb);

}  // namespace weft
