#pragma once
// JPEG and TIFF previews, and images other than plain EXRs read back (OpenEXR
// reads and writes those itself: core/image/io/exr_reader.hpp, exr_writer.hpp;
// libpng writes PNG previews: png_writer.hpp), are encoded and decoded by
// OpenImageIO, kept behind this small interface in its own shared module
// (weft_oiio.so beside the executable, loaded the first time one is needed:
// core/base/files/module_loader.hpp). OpenImageIO links
// about 260 shared libraries; resolving their symbols at start-up would cost
// every weft process a tenth of a second, including the many short renders
// of a benchmark or a farm.
#include <string>
#include <utility>
#include <vector>

namespace weft {

// What a file holds besides its pixels, in both directions.
struct ImageFileSpec {
    int width = 0, height = 0;
    std::vector<std::string> channels;
    bool uint8 = false;                // pixels are 8-bit (previews) instead of 32-bit float
    int x = 0, y = 0;                  // data window origin inside the display window
    int fullWidth = 0, fullHeight = 0; // display window
    std::vector<std::pair<std::string, std::string>> attributes;  // string header attributes
};

struct ImageCodec {
    int abiVersion;
    // Writes pixels (float, or uint8 when spec.uint8) to path; returns "" or what went wrong.
    std::string (*write)(const std::string& path, const ImageFileSpec& spec, const void* pixels);
    // Reads any image as float; fills spec and pixels; returns "" or what went wrong.
    std::string (*read)(const std::string& path, ImageFileSpec& spec, std::vector<float>& pixels);
};

constexpr int kImageCodecAbi = 1;

// The module, loaded once (thread-safe); a weft::Error names the paths tried.
const ImageCodec& imageCodec();

}  // namespace weft

// The module's one entry point.
extern "C" const void* weft_image_codec();  // the module's ImageCodec
