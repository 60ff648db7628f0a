#include "core/image/image_io.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/base/atomic_file.hpp"
#include "core/image/color.hpp"
#include "core/base/error.hpp"
#include "core/base/input_file.hpp"
#include "core/image/exr_preflight.hpp"
#include "core/image/exr_reader.hpp"
#include "core/image/exr_writer.hpp"
#include "core/image/image_codec.hpp"

namespace weft {

namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

void writeAtomically(const std::string& path, const ImageFileSpec& spec, const void* pixels) {
    AtomicOutput out(path);
    const std::string error = imageCodec().write(out.tempPath(), spec, pixels);
    if (!error.empty()) throw Error("cannot write '" + path + "': " + error);
    out.commit();
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

Image readImage(const std::string& path, Metadata* metadata, ImageWindow* window) {
    requireRegularFile(path, "image");
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
    std::vector<float> rgb(static_cast<std::size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* dst = &rgb[(static_cast<std::size_t>(y) * w + x) * 3];
            dst[0] = image.at(x, y, r), dst[1] = image.at(x, y, g), dst[2] = image.at(x, y, b);
        }
    displayTransform().apply(rgb.data(), w * h);
    std::vector<unsigned char> bytes(rgb.size());
    for (std::size_t i = 0; i < rgb.size(); ++i) {
        const float v = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.0f, 1.0f) : 0.0f;
        bytes[i] = static_cast<unsigned char>(std::lround(v * 255.0f));
    }
    ImageFileSpec spec;
    spec.width = w, spec.height = h, spec.fullWidth = w, spec.fullHeight = h;
    spec.channels = {"R", "G", "B"};
    spec.uint8 = true;
    spec.attributes = {{"oiio:ColorSpace", "sRGB"}};
    writeAtomically(path, spec, bytes.data());
}

}  // namespace weft
