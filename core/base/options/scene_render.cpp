#include "core/base/options/scene_render.hpp"

#include <cstdio>

#include "core/base/error.hpp"

namespace weft {

namespace {

constexpr int kMaxSide = 65536;

Error badResolution(const std::string& text) {
    return Error("bad resolution '" + text + "': expected WxH with W and H in [1, 65536], e.g. 512x512");
}

}  // namespace

bool Resolution::valid() const { return width >= 1 && height >= 1 && width <= kMaxSide && height <= kMaxSide; }

std::string Resolution::text() const { return std::to_string(width) + "x" + std::to_string(height); }

std::optional<Resolution> readResolution(const std::string& text) {
    Resolution r;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &r.width, &x, &r.height, &extra) != 3 || (x != 'x' && x != 'X') || !r.valid())
        return std::nullopt;
    return r;
}

Resolution parseResolution(const std::string& text) {
    if (const std::optional<Resolution> r = readResolution(text)) return *r;
    throw badResolution(text);
}

void requireValid(const Resolution& resolution) {
    if (!resolution.valid()) throw badResolution(resolution.text());
}

}  // namespace weft
