#include "core/image/exr_writer.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include "core/base/error.hpp"

namespace weft {

void writeExrFile(const std::string& path, const Image& image,
                  const std::vector<std::pair<std::string, std::string>>& attributes, int x, int y, int fullWidth,
                  int fullHeight) {
    const int w = image.width(), h = image.height(), n = image.channelCount();
    const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(fullWidth - 1, fullHeight - 1));
    const Imath::Box2i data(Imath::V2i(x, y), Imath::V2i(x + w - 1, y + h - 1));
    Imf::Header header(display, data, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, Imf::ZIP_COMPRESSION);
    // Attributes read back from an EXR (weft merge) also name the header's own
    // typed ones (compression, windows...): those the header already holds stay.
    for (const auto& [key, value] : attributes)
        if (header.find(key) == header.end() || header.findTypedAttribute<Imf::StringAttribute>(key) != nullptr)
            header.insert(key, Imf::StringAttribute(value));
    Imf::FrameBuffer frame;
    const std::size_t xStride = sizeof(float) * n, yStride = xStride * w;
    // OpenEXR addresses pixels by their frame coordinates: shift the base by the data window's origin.
    const char* base = reinterpret_cast<const char*>(image.pixel(0, 0)) - x * xStride - y * yStride;
    for (int c = 0; c < n; ++c) {
        header.channels().insert(image.channelNames()[c], Imf::Channel(Imf::FLOAT));
        frame.insert(image.channelNames()[c], Imf::Slice(Imf::FLOAT, const_cast<char*>(base) + c * sizeof(float), xStride, yStride));
    }
    try {
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(h);
    } catch (const std::exception& e) {
        throw Error("cannot write '" + path + "': " + e.what());
    }
}

}  // namespace weft
