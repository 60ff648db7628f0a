// The image codec module (weft_oiio.so): OpenImageIO behind
// core/image/image_codec.hpp, so that only processes that touch image files load it.
#include <OpenImageIO/imageio.h>

#include "core/image/image_codec.hpp"

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

std::string readImage(const std::string& path, ImageFileSpec& f, std::vector<float>& pixels) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return "cannot be read (" + OIIO::geterror() + ")";
    const OIIO::ImageSpec& spec = in->spec();
    f.width = spec.width, f.height = spec.height;
    f.channels = spec.channelnames;
    f.x = spec.x - spec.full_x, f.y = spec.y - spec.full_y;
    f.fullWidth = spec.full_width, f.fullHeight = spec.full_height;
    pixels.resize(std::size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())) return in->geterror();
    for (const auto& attr : spec.extra_attribs)
        if (attr.type() == OIIO::TypeDesc::STRING) f.attributes.emplace_back(attr.name().string(), attr.get_string());
    return "";
}

const weft::ImageCodec kCodec{weft::kImageCodecAbi, writeImage, readImage};

}  // namespace

extern "C" const weft::ImageCodec* weft_image_codec() { return &kCodec; }
