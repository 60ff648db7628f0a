#pragma once
// EXR files are read with OpenEXR itself, as they are written
// (core/image/io/exr_writer.hpp): a diff, a sweep's reference, a farm's frame
// check or a tile merge then starts without loading OpenImageIO's some 260
// libraries, which took longer than reading the pixels. What OpenEXR's
// scanline interface cannot hand over as plain float pixels (deep data,
// subsampled channels, luminance-chroma files that OpenImageIO turns into
// RGB) is left to OpenImageIO (core/image/io/image_codec.hpp).
#include <string>
#include <vector>

#include "core/image/io/image_codec.hpp"

namespace weft {

enum class ExrRead { Read, NeedsCodec };

// Reads the first part as float, interleaved; fills spec as the codec does:
// channels in OpenImageIO's order (exrChannelOrder), the data window's origin
// relative to the display window, the compression's name ("compression"),
// and the header's string attributes under their OpenEXR names. Half and float channels read as OpenImageIO reads
// them; a uint channel (an ID) reads as its integer values, where OpenImageIO
// scales it to [0, 1]. A file that cannot be read throws a weft::Error naming
// path and what is wrong.
ExrRead readExrFile(const std::string& path, ImageFileSpec& spec, std::vector<float>& pixels);

// The order OpenImageIO hands an EXR's channels in, so an image reads the
// same whichever library read it: by layer (the name up to its last '.',
// none first), then R, G, B, Y, A, Z... in that order (case ignored; X, Y, Z
// together after colour in a layer that holds X and Y or Z), then by name.
// Returns indices into `names`.
std::vector<int> exrChannelOrder(const std::vector<std::string>& names);

}  // namespace weft
