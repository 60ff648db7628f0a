#include "core/image/exr_writer.hpp"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <cmath>

#include "core/base/error.hpp"

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

// A channel as half: out-of-range values saturate at the largest finite half
// (a float beyond 65504 would become Inf), NaN is written as 0.
std::vector<Imath::half> halfPlane(const Image& image, int c) {
    const int w = image.width(), h = image.height();
    std::vector<Imath::half> plane(std::size_t(w) * h);
    const float top = float(HALF_MAX);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float v = image.at(x, y, c);
            plane[std::size_t(y) * w + x] = Imath::half(std::isnan(v) ? 0.0f : std::clamp(v, -top, top));
        }
    return plane;
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
    std::vector<std::vector<Imath::half>> halfPlanes(n);
    Imf::FrameBuffer frame;
    const std::size_t xStride = sizeof(float) * n, yStride = xStride * w;
    // OpenEXR addresses pixels by their frame coordinates: shift the base by the data window's origin.
    const char* base = reinterpret_cast<const char*>(image.pixel(0, 0)) - x * xStride - y * yStride;
    for (int c = 0; c < n; ++c) {
        const std::string& name = image.channelNames()[c];
        if (half[c]) {
            halfPlanes[c] = halfPlane(image, c);
            const std::size_t hx = sizeof(Imath::half), hy = hx * w;
            char* origin = reinterpret_cast<char*>(halfPlanes[c].data()) - x * hx - y * hy;
            header.channels().insert(name, Imf::Channel(Imf::HALF));
            frame.insert(name, Imf::Slice(Imf::HALF, origin, hx, hy));
        } else {
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            frame.insert(name, Imf::Slice(Imf::FLOAT, const_cast<char*>(base) + c * sizeof(float), xStride, yStride));
        }
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
