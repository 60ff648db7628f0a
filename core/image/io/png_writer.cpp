#include "core/image/io/png_writer.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace weft {

std::string writePngRgb8(const std::string& path, int width, int height, const unsigned char* rgb) {
    if (width <= 0 || height <= 0) return "a PNG needs at least one pixel";
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) return std::strerror(errno);
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = static_cast<png_uint_32>(width);
    image.height = static_cast<png_uint_32>(height);
    image.format = PNG_FORMAT_RGB;  // 8-bit, sRGB encoded: libpng writes the sRGB chunk
    errno = 0;
    const bool encoded = png_image_write_to_stdio(&image, file, /*convert_to_8bit=*/0, rgb, /*row_stride=*/0, nullptr);
    const int writeError = errno;
    if (!encoded) png_image_free(&image);
    const bool closed = std::fclose(file) == 0;  // a full disk may show only here
    if (!encoded) return writeError ? std::strerror(writeError) : "the PNG encoder failed";
    if (!closed) return std::strerror(errno);
    return "";
}

}  // namespace weft
