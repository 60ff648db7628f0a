// The image codec module (weft_oiio.so): OpenImageIO behind
// core/image/io/image_codec.hpp, so that only processes that touch image files load it.
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <memory>
#include <string>

#include "core/base/memory/physical_memory.hpp"
#include "core/image/io/image_codec.hpp"

namespace {

using weft::ImageFileSpec;

std::string writeImage(const std::string& path, const ImageFileSpec& f, const void* pixels) {
    OIIO::ImageSpec spec(f.width, f.height, int(f.channels.size()), f.uint8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
    spec.x = f.x, spec.y = f.y;
    spec.full_x = 0, spec.full_y = 0;
    spec.full_width = f.fullWidth, spec.full_height = f.fullHeight;
    spec.channelnames = f.channels;
    for (std::size_t c = 0; c < f.channels.size(); ++c) {
        if (f.channels[c] == "A") spec.alpha_channel = int(c);
        if (f.channels[c] == "Z") spec.z_channel = int(c);
    }
    for (const auto& [key, value] : f.attributes) spec.attribute(key, value);
    auto writer = OIIO::ImageOutput::create(path);
    if (!writer) return "no image writer for this extension";
    if (!writer->open(path, spec) || !writer->write_image(spec.format, pixels) || !writer->close())
        return writer->geterror();
    return "";
}

// Pixels a header may claim before reading is refused: half of physical
// memory (a corrupt or hostile header must not reach the allocator).
double maxPixelBytes() { return weft::physicalMemoryBytes() / 2; }

// The library's messages stay inside the module: the caller gets what went
// wrong in weft's words.
// The reader of the file's extension. OpenImageIO's open(path) tries every
// other format's reader on a file its own reader refuses, which is slow on a
// corrupt file and names the wrong format; only a name without a known
// extension is left to that search.
std::unique_ptr<OIIO::ImageInput> openByExtension(const std::string& path) {
    const std::size_t slash = path.find_last_of('/'), dot = path.find_last_of('.');
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash) && dot + 1 < path.size()) {
        if (auto in = OIIO::ImageInput::create(path.substr(dot + 1))) {
            OIIO::ImageSpec spec;
            if (in->open(path, spec)) return in;
            in->geterror();  // clear it
            return nullptr;
        }
        OIIO::geterror();
    }
    return OIIO::ImageInput::open(path);
}

std::string readPixels(const std::string& path, ImageFileSpec& f, std::vector<float>& pixels) {
    auto in = openByExtension(path);
    if (!in) {
        OIIO::geterror();  // clear it
        return "cannot be read: not an image file, or its header is corrupt";
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        return "cannot be read: its header gives no pixels";
    const double bytes = double(spec.width) * spec.height * spec.nchannels * sizeof(float);
    if (bytes > maxPixelBytes()) {
        char text[160];
        std::snprintf(text, sizeof text, "its header claims %dx%d pixels of %d channels (%.1f GiB as float), more than half of this machine's memory",
                      spec.width, spec.height, spec.nchannels, bytes / double(1 << 30));
        return text;
    }
    f.width = spec.width, f.height = spec.height;
    f.channels = spec.channelnames;
    f.x = spec.x - spec.full_x, f.y = spec.y - spec.full_y;
    f.fullWidth = spec.full_width, f.fullHeight = spec.full_height;
    pixels.resize(std::size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())) {
        in->geterror();  // clear it
        return "cannot be read: its pixel data is cut short or corrupt";
    }
    for (const auto& attr : spec.extra_attribs)
        if (attr.type() == OIIO::TypeDesc::STRING) f.attributes.emplace_back(attr.name().string(), attr.get_string());
    return "";
}

std::string readImage(const std::string& path, ImageFileSpec& f, std::vector<float>& pixels) {
    try {
        return readPixels(path, f, pixels);
    } catch (const std::bad_alloc&) {
        return "cannot be read: not enough memory for its pixels";
    } catch (const std::exception&) {
        return "cannot be read: the file is corrupt";
    }
}

const weft::ImageCodec kCodec{weft::kImageCodecAbi, writeImage, readImage};

}  // namespace

// `const void*`, the type loadModule calls it through (core/base/files/module_loader.hpp).
extern "C" const void* weft_image_codec() { return &kCodec; }
