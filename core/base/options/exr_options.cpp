#include "core/base/options/exr_options.hpp"

#include <algorithm>

#include "core/base/error.hpp"

namespace weft {

namespace {

bool isBeauty(const std::string& channel) { return channel == "R" || channel == "G" || channel == "B" || channel == "A"; }

// Whether `selector` (a channel, a layer, or aovs) covers `channel`.
bool selects(const std::string& selector, const std::string& channel) {
    if (selector == "aovs") return !isBeauty(channel);
    return channel == selector || (channel.size() > selector.size() && channel.compare(0, selector.size(), selector) == 0 &&
                                   channel[selector.size()] == '.');
}

struct Spec {
    std::string selector;  // "" = every channel
    bool half = false;
};

Spec parseSpec(const std::string& text) {
    const std::size_t eq = text.rfind('=');
    const std::string type = eq == std::string::npos ? text : text.substr(eq + 1);
    const std::string selector = eq == std::string::npos ? "" : text.substr(0, eq);
    if ((type != "half" && type != "float") || (eq != std::string::npos && selector.empty()))
        throw Error("'" + text + "': expected half or float, or CHANNEL=half|float (a channel, a layer such as N, or aovs)");
    return {selector, type == "half"};
}

}  // namespace

const std::vector<std::string>& exrCompressionNames() {
    static const std::vector<std::string> names{"none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"};
    return names;
}

bool exrCompressionIsLossless(const std::string& name) {
    return name == "none" || name == "rle" || name == "zips" || name == "zip" || name == "piz";
}

void checkPixelTypeSpec(const std::string& spec) { parseSpec(spec); }

std::vector<bool> halfChannels(const std::vector<std::string>& channels, const std::vector<std::string>& specs,
                               std::vector<std::string>* unmatched) {
    std::vector<bool> half(channels.size(), false);
    for (const std::string& text : specs) {
        const Spec s = parseSpec(text);
        bool matched = false;
        for (std::size_t c = 0; c < channels.size(); ++c)
            if (s.selector.empty() || selects(s.selector, channels[c])) half[c] = s.half, matched = true;
        if (!matched && unmatched) unmatched->push_back(text);
    }
    return half;
}

std::string pixelTypesText(const std::vector<std::string>& channels, const std::vector<bool>& half) {
    const auto halves = std::count(half.begin(), half.end(), true);
    if (halves == 0) return "float";
    if (halves == std::ptrdiff_t(half.size())) return "half";
    std::string floats, halfs;
    for (std::size_t c = 0; c < channels.size(); ++c) {
        std::string& list = half[c] ? halfs : floats;
        list += (list.empty() ? "" : ",") + channels[c];
    }
    return floats + " float; " + halfs + " half";
}

}  // namespace weft
