#pragma once
// How a render's EXR is encoded (the options --compression and -d, and
// what core/image/io/exr_writer.cpp does with them): OpenEXR's compression, each channel's pixel
// type (oiiotool's -d: `half`, `float`, or CHANNEL=TYPE, where CHANNEL is a
// channel, a layer such as `N` for N.X/N.Y/N.Z, or `aovs` for every channel
// but R, G, B and A) and the threads OpenEXR compresses with. The same
// pixels and encoding give the same bytes on any thread count.
#include <string>
#include <vector>

namespace weft {

// The names --compression takes, in OpenEXR's order (a name's index is
// its Imf::Compression value).
const std::vector<std::string>& exrCompressionNames();
// Whether a compression returns every channel bit for bit (pxr24 rounds
// floats to 24 bits; b44 and b44a are lossy on half channels, dwaa and dwab
// on colour channels of either type: R, G, B and Y, also as the last part
// of a layer's name, so N.Y too).
bool exrCompressionIsLossless(const std::string& name);
// The default: lossless, and the quickest to write of those that compress a
// render's frame at all (bench/exr_write.py measures every one).
inline constexpr const char* kDefaultExrCompression = "rle";

// Throws "'SPEC': ..." unless SPEC is TYPE or CHANNEL=TYPE with TYPE half or float.
void checkPixelTypeSpec(const std::string& spec);
// Per channel, whether it is written as half: the specs apply in order, later
// ones win. A CHANNEL=TYPE that names no channel of the image is reported
// in `unmatched` (the caller warns: another technique's AOVs may differ).
std::vector<bool> halfChannels(const std::vector<std::string>& channels, const std::vector<std::string>& specs,
                               std::vector<std::string>* unmatched = nullptr);
// "float" or "half" when every channel has that type, else e.g.
// "R,G,B,A float; N.X,N.Y,N.Z half" (the weft:pixel_types attribute).
std::string pixelTypesText(const std::vector<std::string>& channels, const std::vector<bool>& half);

struct ExrEncoding {
    std::string compression = kDefaultExrCompression;
    std::vector<std::string> pixelTypes;  // -d specs, in order
    int threads = 1;                      // OpenEXR's compression threads
};

}  // namespace weft
