#include "core/base/options/frames.hpp"

#include <algorithm>

#include <cctype>
#include <cstdio>

#include "core/base/error.hpp"

namespace weft {

namespace {

constexpr long kFrameLimit = 1000000000;  // |frame| bound: keeps padding and arithmetic in int
constexpr std::size_t kMaxFrames = 1000000;

// Reads an optionally signed integer at text[pos]; advances pos. Empty optional on no digits.
std::optional<long> readInt(const std::string& text, std::size_t& pos, bool allowSign) {
    std::size_t p = pos;
    bool negative = false;
    if (allowSign && p < text.size() && text[p] == '-') negative = true, ++p;
    const std::size_t digits = p;
    long value = 0;
    while (p < text.size() && std::isdigit(static_cast<unsigned char>(text[p]))) {
        value = value * 10 + (text[p] - '0');
        if (value > kFrameLimit) return std::nullopt;
        ++p;
    }
    if (p == digits) return std::nullopt;
    pos = p;
    return negative ? -value : value;
}

[[noreturn]] void badRange(const std::string& text, const std::string& why) {
    throw Error("bad frame range '" + text + "': " + why +
                " (expected e.g. 1001-1100x2, 1,3,5-9 or -5--1)");
}

void appendItem(const std::string& item, const std::string& text, std::vector<int>& frames) {
    std::size_t pos = 0;
    const auto first = readInt(item, pos, true);
    if (!first) badRange(text, "'" + item + "' is not a frame number");
    long last = *first, step = 1;
    if (pos < item.size() && item[pos] == '-') {
        ++pos;
        const auto end = readInt(item, pos, true);
        if (!end) badRange(text, "'" + item + "' has no end frame");
        last = *end;
        if (pos < item.size() && item[pos] == 'x') {
            ++pos;
            const auto s = readInt(item, pos, false);
            if (!s || *s < 1) badRange(text, "the step in '" + item + "' must be a whole number >= 1");
            step = *s;
        }
    }
    if (pos != item.size()) badRange(text, "unexpected '" + item.substr(pos) + "' in '" + item + "'");
    const long dir = last >= *first ? 1 : -1;
    for (long f = *first; dir > 0 ? f <= last : f >= last; f += dir * step) {
        if (frames.size() >= kMaxFrames) badRange(text, "more than 1000000 frames");
        frames.push_back(int(f));
    }
}

}  // namespace

std::vector<int> parseFrameRange(const std::string& text) {
    if (text.empty()) badRange(text, "it is empty");
    std::vector<int> frames;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = text.find(',', start);
        const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (item.empty()) badRange(text, "an empty item between commas");
        appendItem(item, text, frames);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    // A sorted copy finds a repeat in one pass (a set of a million frames
    // took seconds under the sanitizers).
    std::vector<int> sorted = frames;
    std::sort(sorted.begin(), sorted.end());
    if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
        badRange(text, "frame " + std::to_string(*twice) + " is listed twice");
    return frames;
}

namespace {

struct Wildcard {
    std::size_t pos = std::string::npos;
    std::size_t length = 0;
    int width = 0;
};

Wildcard findWildcard(const std::string& name) {
    Wildcard w;
    const std::size_t hash = name.find_first_of("#@");
    std::size_t pct = name.find('%');
    // "%0Nd" or "%d"
    while (pct != std::string::npos) {
        std::size_t p = pct + 1;
        int width = 0;
        // Past 32 the width is refused anyway: stop adding digits before int overflows.
        for (; p < name.size() && std::isdigit(static_cast<unsigned char>(name[p])); ++p)
            if (width <= 32) width = width * 10 + (name[p] - '0');
        if (p < name.size() && name[p] == 'd' && width <= 32) break;
        pct = name.find('%', pct + 1);
    }
    if (hash != std::string::npos && (pct == std::string::npos || hash < pct)) {
        w.pos = hash;
        for (std::size_t p = hash; p < name.size() && (name[p] == '#' || name[p] == '@'); ++p) {
            w.width += name[p] == '#' ? 4 : 1;
            ++w.length;
        }
    } else if (pct != std::string::npos) {
        w.pos = pct;
        std::size_t p = pct + 1;
        while (std::isdigit(static_cast<unsigned char>(name[p]))) w.width = w.width * 10 + (name[p++] - '0');
        w.length = p + 1 - pct;
    }
    return w;
}

}  // namespace

bool hasFrameWildcard(const std::string& name) { return findWildcard(name).pos != std::string::npos; }

std::string expandFrameName(const std::string& name, int frame) {
    const Wildcard w = findWildcard(name);
    if (w.pos == std::string::npos) return name;
    // Sixteen or more '#' ask for 64 digits or more: size the text to fit.
    std::string digits(std::size_t(w.width) + 16, '\0');
    digits.resize(std::size_t(std::snprintf(digits.data(), digits.size(), "%0*d", w.width, frame)));
    return name.substr(0, w.pos) + digits + name.substr(w.pos + w.length);
}

RowBand tileRows(int height, int index, int count) {
    if (count < 1 || index < 1 || index > count)
        throw Error("tile " + std::to_string(index) + "/" + std::to_string(count) + ": expected 1 <= i <= n");
    if (count > height)
        throw Error("--tile " + std::to_string(index) + "/" + std::to_string(count) + ": more tiles than the image's " +
                    std::to_string(height) + " rows");
    const auto edge = [&](int i) { return int(static_cast<long long>(i) * height / count); };
    return {edge(index - 1), edge(index)};
}

bool TileSpec::valid() const { return count >= 1 && count <= 65536 && index >= 1 && index <= count; }

std::string TileSpec::text() const { return std::to_string(index) + "/" + std::to_string(count); }

namespace {

Error badTile(const std::string& text) {
    return Error("bad tile '" + text + "': expected i/n with 1 <= i <= n <= 65536, e.g. 2/4");
}

}  // namespace

TileSpec parseTileSpec(const std::string& text) {
    TileSpec t;
    char slash = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &t.index, &slash, &t.count, &extra) != 3 || slash != '/' || !t.valid())
        throw badTile(text);
    return t;
}

void requireValid(const TileSpec& tile) {
    if (!tile.valid()) throw badTile(tile.text());
}

}  // namespace weft
