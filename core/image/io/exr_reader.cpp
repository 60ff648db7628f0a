#include "core/image/io/exr_reader.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <cstdio>
#include <numeric>
#include <strings.h>
#include <tuple>

#include "core/base/error.hpp"
#include "core/base/options/exr_options.hpp"
#include "core/base/memory/physical_memory.hpp"

namespace weft {

namespace {

// OpenImageIO's ranks of well-known channel names (case ignored); the rest
// come after them, by name. A layer with X and Y or Z (a position, a
// normal) ranks X, Y, Z together after colour.
constexpr const char* kRanked[] = {"R",  "Red", "G",  "Green", "B",  "Blue", "Y",  "real", "imag", "A",
                                   "Alpha", "AR", "RA", "AG", "GA", "AB", "BA", "Z", "Depth", "Zback"};
constexpr const char* kRankedXyz[] = {"R",  "Red",  "G",     "Green", "B",  "Blue", "X",  "Y",  "Z",     "real",
                                      "imag", "A", "Alpha", "AR",    "RA", "AG",   "GA", "AB", "Depth", "Zback"};
constexpr int kUnranked = int(std::size(kRanked));
static_assert(std::size(kRankedXyz) == std::size(kRanked));

int rankOf(const std::string& suffix, const char* const (&ranked)[kUnranked]) {
    for (int i = 0; i < kUnranked; ++i)
        if (strcasecmp(suffix.c_str(), ranked[i]) == 0) return i;
    return kUnranked;
}

struct ChannelName {
    std::string layer, suffix;  // split after the last '.'
};

ChannelName split(const std::string& name) {
    const std::size_t dot = name.find_last_of('.');
    const std::size_t cut = dot == std::string::npos ? 0 : dot + 1;
    return {name.substr(0, cut), name.substr(cut)};
}

bool layerHas(const std::vector<ChannelName>& names, const std::string& layer, const char* suffix) {
    return std::any_of(names.begin(), names.end(),
                       [&](const ChannelName& n) { return n.layer == layer && strcasecmp(n.suffix.c_str(), suffix) == 0; });
}

// Y, RY, BY (and A): OpenImageIO converts luminance-chroma files to RGB.
bool luminanceChroma(const std::vector<std::string>& names) {
    std::vector<ChannelName> split_;
    for (const std::string& n : names) split_.push_back(split(n));
    const auto has = [&](const char* s) {
        return std::any_of(split_.begin(), split_.end(), [&](const ChannelName& n) { return strcasecmp(n.suffix.c_str(), s) == 0; });
    };
    const bool alpha = names.size() == 4 && (has("A") || has("Alpha"));
    return (names.size() == 3 || alpha) && has("Y") && has("RY") && has("BY");
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw Error("image '" + path + "': " + what);
}

// Refused before allocating, as the codec refuses it: half of physical memory.
void checkPixelBytes(const std::string& path, int w, int h, int channels) {
    const double bytes = double(w) * h * channels * sizeof(float);
    if (bytes <= physicalMemoryBytes() / 2) return;
    char text[200];
    std::snprintf(text, sizeof text,
                  "its header claims %dx%d pixels of %d channels (%.1f GiB as float), more than half of this machine's memory",
                  w, h, channels, bytes / double(1 << 30));
    fail(path, text);
}

bool plainPixels(const Imf::Header& header) {
    if (header.hasType() && Imf::isDeepData(header.type())) return false;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
        if (it.channel().xSampling != 1 || it.channel().ySampling != 1) return false;
    return true;
}

void readPixels(Imf::InputFile& file, const std::vector<std::string>& channels, ImageFileSpec& spec,
                std::vector<float>& pixels) {
    const Imath::Box2i data = file.header().dataWindow();
    const std::size_t n = channels.size(), xStride = n * sizeof(float), yStride = xStride * std::size_t(spec.width);
    pixels.assign(std::size_t(spec.width) * std::size_t(spec.height) * n, 0.0f);
    // OpenEXR addresses pixels by their frame coordinates: shift the base by the data window's origin.
    char* origin = reinterpret_cast<char*>(pixels.data()) - std::ptrdiff_t(data.min.x) * std::ptrdiff_t(xStride) -
                   std::ptrdiff_t(data.min.y) * std::ptrdiff_t(yStride);
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < n; ++c)
        frame.insert(channels[c], Imf::Slice(Imf::FLOAT, origin + c * sizeof(float), xStride, yStride));
    file.setFrameBuffer(frame);
    file.readPixels(data.min.y, data.max.y);
}

}  // namespace

std::vector<int> exrChannelOrder(const std::vector<std::string>& names) {
    std::vector<ChannelName> parts;
    for (const std::string& n : names) parts.push_back(split(n));
    std::vector<int> ranks;
    for (const ChannelName& p : parts) {
        const bool xyz = layerHas(parts, p.layer, "X") && (layerHas(parts, p.layer, "Y") || layerHas(parts, p.layer, "Z"));
        ranks.push_back(rankOf(p.suffix, xyz ? kRankedXyz : kRanked));
    }
    std::vector<int> order(names.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
        return std::tie(parts[a].layer, ranks[a], parts[a].suffix) < std::tie(parts[b].layer, ranks[b], parts[b].suffix);
    });
    return order;
}

ExrRead readExrFile(const std::string& path, ImageFileSpec& spec, std::vector<float>& pixels) {
    std::unique_ptr<Imf::InputFile> file;
    try {
        file = std::make_unique<Imf::InputFile>(path.c_str(), Imf::globalThreadCount());
    } catch (const std::exception&) {
        fail(path, "cannot be read: not an image file, or its header is corrupt");
    }
    const Imf::Header& header = file->header();
    std::vector<std::string> fileOrder;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) fileOrder.emplace_back(it.name());
    if (!plainPixels(header) || luminanceChroma(fileOrder)) return ExrRead::NeedsCodec;
    const Imath::Box2i data = header.dataWindow(), display = header.displayWindow();
    const long long w = 1LL + data.max.x - data.min.x, h = 1LL + data.max.y - data.min.y;
    const long long fullW = 1LL + display.max.x - display.min.x, fullH = 1LL + display.max.y - display.min.y;
    const auto inInt = [](long long v) { return v > 0 && v <= INT32_MAX; };
    if (!inInt(w) || !inInt(h) || !inInt(fullW) || !inInt(fullH) || fileOrder.empty())
        fail(path, "cannot be read: its header gives no pixels");
    checkPixelBytes(path, int(w), int(h), int(fileOrder.size()));
    spec.width = int(w), spec.height = int(h);
    spec.x = int(std::clamp<long long>(1LL * data.min.x - display.min.x, INT32_MIN, INT32_MAX));
    spec.y = int(std::clamp<long long>(1LL * data.min.y - display.min.y, INT32_MIN, INT32_MAX));
    spec.fullWidth = int(fullW), spec.fullHeight = int(fullH);
    spec.channels.clear();
    for (int i : exrChannelOrder(fileOrder)) spec.channels.push_back(fileOrder[i]);
    // The compression by name first, as OpenImageIO reports OpenEXR's typed field.
    const std::vector<std::string>& compressions = exrCompressionNames();
    if (std::size_t(header.compression()) < compressions.size())
        spec.attributes.emplace_back("compression", compressions[header.compression()]);
    for (auto it = header.begin(); it != header.end(); ++it)
        if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
            spec.attributes.emplace_back(it.name(), s->value());
    try {
        readPixels(*file, spec.channels, spec, pixels);
    } catch (const std::bad_alloc&) {
        fail(path, "cannot be read: not enough memory for its pixels");
    } catch (const std::exception&) {
        fail(path, "cannot be read: its pixel data is cut short or corrupt");
    }
    return ExrRead::Read;
}

}  // namespace weft
