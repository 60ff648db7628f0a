#include "core/image/io/exr_writer.hpp"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>

#include "core/base/error.hpp"
#include "core/image/io/half_pixels.hpp"

namespace weft {

namespace {

// exrCompressionNames() lists the names in OpenEXR's own order, which the
// file format fixes: a name's index is its Imf::Compression.
static_assert(Imf::NO_COMPRESSION == 0 && Imf::DWAB_COMPRESSION == 9);
Imf::Compression compressionNamed(const std::string& name) {
    const std::vector<std::string>& names = exrCompressionNames();
    const auto it = std::find(names.begin(), names.end(), name);
    if (it != names.end()) return Imf::Compression(it - names.begin());
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    throw Error("--compression '" + name + "': expected one of " + list);
}

}  // namespace

void writeExrFile(const std::string& path, const Image& image,
                  const std::vector<std::pair<std::string, std::string>>& attributes, int x, int y, int fullWidth,
                  int fullHeight, const ExrEncoding& encoding) {
    const int w = image.width(), h = image.height(), n = image.channelCount();
    const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(fullWidth - 1, fullHeight - 1));
    const Imath::Box2i data(Imath::V2i(x, y), Imath::V2i(x + w - 1, y + h - 1));
    Imf::Header header(display, data, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, compressionNamed(encoding.compression));
    // Attributes read back from an EXR (weft merge) also name the header's own
    // typed ones (compression, windows...): those the header already holds stay.
    for (const auto& [key, value] : attributes)
        if (header.find(key) == header.end() || header.findTypedAttribute<Imf::StringAttribute>(key) != nullptr)
            header.insert(key, Imf::StringAttribute(value));
    const std::vector<bool> half = halfChannels(image.channelNames(), encoding.pixelTypes);
    Imf::FrameBuffer frame;
    // Half channels read a half copy of the whole image, interleaved as the
    // float one: one contiguous conversion pass instead of one strided pass a channel.
    std::vector<Imath::half> halves;
    if (std::find(half.begin(), half.end(), true) != half.end()) {
        halves.resize(image.data().size());
        toHalfSaturated(image.data().data(), halves.size(), halves.data());
    }
    // OpenEXR addresses pixels by their frame coordinates: shift each base by the data window's origin.
    const auto originOf = [&](const void* pixels, std::size_t valueBytes) {
        const std::size_t xStride = valueBytes * n, yStride = xStride * w;
        return reinterpret_cast<const char*>(pixels) - x * xStride - y * yStride;
    };
    const char* floatBase = originOf(image.data().data(), sizeof(float));
    const char* halfBase = halves.empty() ? nullptr : originOf(halves.data(), sizeof(Imath::half));
    for (int c = 0; c < n; ++c) {
        const std::string& name = image.channelNames()[c];
        const Imf::PixelType type = half[c] ? Imf::HALF : Imf::FLOAT;
        const std::size_t bytes = half[c] ? sizeof(Imath::half) : sizeof(float);
        char* origin = const_cast<char*>(half[c] ? halfBase : floatBase) + c * bytes;
        header.channels().insert(name, Imf::Channel(type));
        frame.insert(name, Imf::Slice(type, origin, bytes * n, bytes * n * w));
    }
    try {
        // OpenEXR's pool is process-wide: sized once per write to the request's threads.
        const int threads = std::max(1, encoding.threads);
        if (Imf::globalThreadCount() != threads) Imf::setGlobalThreadCount(threads);
        Imf::OutputFile file(path.c_str(), header, threads);
        file.setFrameBuffer(frame);
        file.writePixels(h);
    } catch (const std::exception& e) {
        throw Error("cannot write '" + path + "': " + e.what());
    }
}

}  // namespace weft
