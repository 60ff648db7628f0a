#include "core/image_io.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/atomic_file.hpp"
#include "core/color.hpp"
#include "core/error.hpp"

namespace weft {

namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

void writeWithOiio(const std::string& path, const OIIO::ImageSpec& spec, const void* pixels) {
    AtomicOutput out(path);
    auto writer = OIIO::ImageOutput::create(out.tempPath());
    if (!writer) throw Error("cannot write '" + path + "': no image writer for this extension");
    if (!writer->open(out.tempPath(), spec) || !writer->write_image(spec.format, pixels) || !writer->close())
        throw Error("cannot write '" + path + "': " + writer->geterror());
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

void writeExr(const Image& image, const std::string& path, const Metadata& metadata, const ImageWindow& window) {
    if (lowerExtension(path) != ".exr") throw Error("output '" + path + "': the render output must be an .exr file");
    OIIO::ImageSpec spec(image.width(), image.height(), image.channelCount(), OIIO::TypeDesc::FLOAT);
    spec.x = window.x, spec.y = window.y;
    spec.full_x = 0, spec.full_y = 0;
    spec.full_width = window.fullWidth, spec.full_height = window.fullHeight;
    spec.channelnames = image.channelNames();
    spec.alpha_channel = image.channelIndex("A");
    spec.z_channel = image.channelIndex("Z");
    spec.attribute("compression", "zip");
    spec.attribute("oiio:ColorSpace", "scene_linear");
    spec.attribute("DateTime", "");  // OIIO would stamp the wall clock: same render, same bytes
    for (const auto& [key, value] : metadata) spec.attribute(key, value);
    writeWithOiio(path, spec, image.data().data());
}

Image readImage(const std::string& path, Metadata* metadata, ImageWindow* window) {
    if (!std::filesystem::exists(path)) throw Error("image '" + path + "': no such file");
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw Error("image '" + path + "': cannot be read (" + OIIO::geterror() + ")");
    const OIIO::ImageSpec& spec = in->spec();
    Image image(spec.width, spec.height, spec.channelnames);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.data().data()))
        throw Error("image '" + path + "': " + in->geterror());
    if (window) *window = ImageWindow{spec.x - spec.full_x, spec.y - spec.full_y, spec.full_width, spec.full_height};
    if (metadata) {
        for (const auto& attr : spec.extra_attribs)
            if (attr.type() == OIIO::TypeDesc::STRING) metadata->emplace_back(attr.name().string(), attr.get_string());
    }
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
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    writeWithOiio(path, spec, bytes.data());
}

}  // namespace weft
