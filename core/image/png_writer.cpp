#include "core/image/png_writer.hpp"

#include <png.h>

namespace weft {

std::string writePngRgb8(const std::string& path, int width, int height, const unsigned char* rgb) {
    if (width <= 0 || height <= 0) return "a PNG needs at least one pixel";
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = static_cast<png_uint_32>(width);
    image.height = static_cast<png_uint_32>(height);
    image.format = PNG_FORMAT_RGB;  // 8-bit, sRGB encoded: libpng writes the sRGB chunk
    if (png_image_write_to_file(&image, path.c_str(), /*convert_to_8bit=*/0, rgb, /*row_stride=*/0, nullptr))
        return "";
    std::string error = image.message[0] ? image.message : "libpng failed";
    png_image_free(&image);
    return error;
}

}  // namespace weft
