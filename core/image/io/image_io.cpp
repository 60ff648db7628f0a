#include "core/image/io/image_io.hpp"

#include <algorithm>
#include <filesystem>

#include <tbb/parallel_for.h>

#include "core/base/files/atomic_file.hpp"
#include "core/image/color.hpp"
#include "core/base/error.hpp"
#include "core/base/files/input_file.hpp"
#include "core/image/io/exr_preflight.hpp"
#include "core/image/io/exr_reader.hpp"
#include "core/image/io/exr_writer.hpp"
#include "core/image/io/image_codec.hpp"
#include "core/image/io/png_writer.hpp"

namespace weft {

namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

// Writes path through a temporary file: `write` writes the temporary and
// returns "" or what went wrong.
template <class Write>
void writeAtomically(const std::string& path, Write&& write) {
    AtomicOutput out(path);
    const std::string error = write(out.tempPath());
    if (!error.empty()) throw Error("cannot write '" + path + "': " + error);
    out.commit();
}

// Display-encoded 8-bit RGB of the image's R, G, B, in bands of rows in
// parallel. The bands are fixed, not the threads', so that the transform
// sees the same runs of pixels on any thread count.
std::vector<unsigned char> previewBytes(const Image& image, int r, int g, int b) {
    const int w = image.width(), h = image.height();
    constexpr int kBandRows = 16;
    std::vector<unsigned char> bytes(static_cast<std::size_t>(w) * h * 3);
    const DisplayTransform& display = displayTransform();
    tbb::parallel_for(0, (h + kBandRows - 1) / kBandRows, [&](int band) {
        const int y0 = band * kBandRows, y1 = std::min(h, y0 + kBandRows);
        std::vector<float> rgb(static_cast<std::size_t>(w) * (y1 - y0) * 3);
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                float* dst = &rgb[(static_cast<std::size_t>(y - y0) * w + x) * 3];
                dst[0] = image.at(x, y, r), dst[1] = image.at(x, y, g), dst[2] = image.at(x, y, b);
            }
        display.encode8(rgb.data(), &bytes[static_cast<std::size_t>(y0) * w * 3], w * (y1 - y0));
    });
    return bytes;
}

}  // namespace

bool isPreviewPath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tif" || ext == ".tiff";
}

void writeExr(const Image& image, const std::string& path, const Metadata& metadata) {
    writeExr(image, path, metadata, ImageWindow{0, 0, image.width(), image.height()});
}

void writeExr(const Image& image, const std::string& path, const Metadata& metadata, const ImageWindow& window,
              const ExrEncoding& encoding) {
    if (lowerExtension(path) != ".exr") throw Error("output '" + path + "': the render output must be an .exr file");
    Metadata attributes{{"oiio:ColorSpace", "scene_linear"}};
    attributes.insert(attributes.end(), metadata.begin(), metadata.end());
    AtomicOutput out(path);
    writeExrFile(out.tempPath(), image, attributes, window.x, window.y, window.fullWidth, window.fullHeight, encoding);
    out.commit();
}

// Formats read as images. Others (a .vdb, a scene) are refused before the
// codec sees them: OpenImageIO's OpenVDB reader aborted the process on a
// grid OpenVDB itself asserts on.
bool isImagePath(const std::string& path) {
    static const char* const kImages[] = {".exr", ".png", ".jpg", ".jpeg", ".tif", ".tiff", ".hdr", ".tga", ".bmp", ".ppm", ".pfm", ".dpx"};
    const std::string ext = lowerExtension(path);
    return std::any_of(std::begin(kImages), std::end(kImages), [&](const char* e) { return ext == e; });
}

Image readImage(const std::string& path, Metadata* metadata, ImageWindow* window) {
    requireRegularFile(path, "image");
    if (!isImagePath(path))
        throw Error("image '" + path + "': not an image file weft reads (.exr, .png, .jpg, .tif, .hdr, .tga, .bmp, .ppm, .pfm, .dpx)");
    ImageFileSpec spec;
    std::vector<float> pixels;
    const bool exr = lowerExtension(path) == ".exr";
    if (exr) preflightExr(path);
    if (!exr || readExrFile(path, spec, pixels) == ExrRead::NeedsCodec) {
        spec = {}, pixels.clear();
        const std::string error = imageCodec().read(path, spec, pixels);
        if (!error.empty()) throw Error("image '" + path + "': " + error);
    }
    Image image(spec.width, spec.height, spec.channels);
    image.data().assign(pixels.begin(), pixels.end());
    if (window) *window = ImageWindow{spec.x, spec.y, spec.fullWidth, spec.fullHeight};
    if (metadata) metadata->insert(metadata->end(), spec.attributes.begin(), spec.attributes.end());
    return image;
}

void writePreview(const Image& image, const std::string& path) {
    const int w = image.width(), h = image.height();
    const int r = image.channelIndex("R"), g = image.channelIndex("G"), b = image.channelIndex("B");
    if (r < 0 || g < 0 || b < 0) throw Error("preview '" + path + "': the image has no R, G, B channels");
    const std::vector<unsigned char> bytes = previewBytes(image, r, g, b);
    if (lowerExtension(path) == ".png")  // libpng, without loading OpenImageIO
        return writeAtomically(path, [&](const std::string& temp) { return writePngRgb8(temp, w, h, bytes.data()); });
    ImageFileSpec spec;
    spec.width = w, spec.height = h, spec.fullWidth = w, spec.fullHeight = h;
    spec.channels = {"R", "G", "B"};
    spec.uint8 = true;
    spec.attributes = {{"oiio:ColorSpace", "sRGB"}};
    writeAtomically(path, [&](const std::string& temp) { return imageCodec().write(temp, spec, bytes.data()); });
}

}  // namespace weft
