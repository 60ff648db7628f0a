#pragma once
// Image files (OpenEXR; libpng; OpenImageIO through core/image/io/image_codec.hpp): multi-channel EXR with render metadata,
// and display-referred previews (PNG/JPEG/TIFF) through OpenColorIO.
#include <string>
#include <utility>
#include <vector>

#include "core/base/options/exr_options.hpp"
#include "core/image/image.hpp"

namespace weft {

// Ordered string attributes written into the file header ("weft:technique"...).
using Metadata = std::vector<std::pair<std::string, std::string>>;

// Where an image lies in a larger frame (a tile of it): the origin of its
// pixels (EXR data window) and the frame's size (display window).
struct ImageWindow {
    int x = 0, y = 0;
    int fullWidth = 0, fullHeight = 0;
};

// Writes an EXR atomically: 32-bit float channels, losslessly compressed
// (kDefaultExrCompression), unless `encoding` says otherwise. No time stamps
// are written: same pixels, metadata and encoding give the same bytes.
void writeExr(const Image& image, const std::string& path, const Metadata& metadata);
// The same for a part of a frame: the EXR's data window starts at
// (window.x, window.y) inside a fullWidth x fullHeight display window.
void writeExr(const Image& image, const std::string& path, const Metadata& metadata, const ImageWindow& window,
              const ExrEncoding& encoding = {});

// Reads any image OpenImageIO understands, as float (an EXR through OpenEXR
// itself, core/image/io/exr_reader.hpp); metadata receives the string
// attributes and window the data and display windows, when given.
Image readImage(const std::string& path, Metadata* metadata = nullptr, ImageWindow* window = nullptr);

// Writes an 8-bit display-referred preview (format from the extension:
// PNG through libpng, core/image/io/png_writer.hpp; JPEG and TIFF through
// OpenImageIO), composited over black, through the OCIO display transform;
// atomically.
void writePreview(const Image& image, const std::string& path);

// Whether the extension names a preview format (not EXR).
bool isPreviewPath(const std::string& path);

}  // namespace weft
