#pragma once
// Fuzz target: the small text parsers of the command line, batch jobs and
// scene files. Byte 0 picks the parser, the rest is its text:
//   0 frame ranges      1 frame-numbered names   2 tiles and their row bands
//   3 resolutions       4 a render request, one "option value" per line,
//                         validated as `weft render` does before loading
//   5 technique parameters, byte 1 picks the technique, "key=value" lines
//   6 raw-import options (--dims, --spacing)
// Each accepted text is checked against what its header promises.
#include <algorithm>
#include <cstdlib>
#include <map>
#include <vector>

#include "core/base/options/frames.hpp"
#include "core/base/options/render_options.hpp"
#include "core/volume/io/raw_volume.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/render_cli.hpp"
#include "plugins/host/render_job.hpp"
#include "plugins/technique.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace weft::fuzz {

inline std::vector<std::string> textLines(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        lines.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return lines;
}

inline void frameRange(const std::string& text) {
    const std::vector<int> frames = parseFrameRange(text);
    require(!frames.empty() && frames.size() <= 1000000, "1 to 10^6 frames", text);
    // Sorted, not a std::set: a million set nodes took seconds under ASan.
    std::vector<int> sorted = frames;
    std::sort(sorted.begin(), sorted.end());
    require(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end(), "no frame twice", text);
    for (int f : frames) require(std::abs(f) <= 1000000000, "frames within +-10^9", text);
}

// printf's "%0*d": the sign first, then zeros up to the width.
inline std::string zeroPadded(int frame, int width) {
    const std::string digits = std::to_string(std::abs(static_cast<long long>(frame)));
    const std::string sign = frame < 0 ? "-" : "";
    const std::size_t pad = std::size_t(std::max<long long>(0, width - (long long)(sign.size() + digits.size())));
    return sign + std::string(pad, '0') + digits;
}

inline void frameName(const std::string& text) {
    if (text.empty()) return;
    static constexpr int kFrames[] = {0, 7, -5, 1001, 1000000000, -1000000000};
    const int frame = kFrames[static_cast<unsigned char>(text[0]) % std::size(kFrames)];
    const std::string name = text.substr(1);
    const std::string expanded = expandFrameName(name, frame);
    require(hasFrameWildcard(name) || expanded == name, "a name without wildcard is unchanged", name);
    // A name whose only special characters are one run of '#': each is 4 digits.
    const std::size_t hash = name.find('#');
    if (hash == std::string::npos || name.find_first_of("@%") != std::string::npos) return;
    const std::size_t end = name.find_first_not_of('#', hash);
    const std::size_t run = (end == std::string::npos ? name.size() : end) - hash;
    if (name.find('#', hash + run) != std::string::npos) return;
    require(expanded == name.substr(0, hash) + zeroPadded(frame, int(4 * run)) + name.substr(hash + run),
            "'#' expands to 4 digits each", name);
}

inline void tiles(const std::string& text) {
    const auto [index, count] = parseTileSpec(text);
    require(1 <= index && index <= count && count <= 65536, "1 <= i <= n <= 65536", text);
    for (int height : {count, count + 1, 1080, 65536}) {
        if (height < count) continue;
        const RowBand band = tileRows(height, index, count);
        const int rows = band.end - band.begin;
        require(0 <= band.begin && band.end <= height && (rows == height / count || rows == height / count + 1),
                "bands within the image, sizes differ by at most one row", text);
    }
}

inline void resolution(const std::string& text) {
    const auto [w, h] = parseResolution(text);
    require(1 <= w && w <= 65536 && 1 <= h && h <= 65536, "sizes in [1, 65536]", text);
    require(parseResolution(std::to_string(w) + "x" + std::to_string(h)) == Resolution{w, h}, "round trip", text);
}

// Lines "name value" as `weft render --name value` would give them.
inline void renderRequest(const std::string& text) {
    RenderRequest r;
    for (const std::string& line : textLines(text)) {
        const std::size_t space = line.find(' ');
        const std::string name = line.substr(0, space), value = space == std::string::npos ? "" : line.substr(space + 1);
        const RenderOption* option = findRenderOption(name, kOnCommandLine);
        if (!option) continue;
        applyRenderOption(r, *option, value, commandLineLabel(*option));
    }
    validateRequest(r);
    if (r.frames) {
        const std::vector<int>& frames = *r.frames;
        if (frames.size() <= 1000) requestsForFrames(r, frames);  // each frame copies the request
    }
}

inline void techniqueParams(const std::string& text) {
    if (text.empty()) return;
    const std::vector<const TechniqueInfo*> all = techniques().all();
    const TechniqueInfo& info = *all[static_cast<unsigned char>(text[0]) % all.size()];
    std::map<std::string, std::string> given;
    for (const std::string& line : textLines(text.substr(1))) {
        auto [k, v] = splitKeyValue(line, "--set");
        given[k] = v;
    }
    const ParamSet set = info.params.parse(given);
    require(set.values().size() == info.params.specs().size(), "every parameter has a value", text);
}

inline void rawOptions(const std::string& text) {
    const std::size_t cut = text.find('\n');
    const openvdb::Coord d = parseRawDims(text.substr(0, cut));
    require(d.x() > 0 && d.y() > 0 && d.z() > 0, "positive dims", text);
    if (cut == std::string::npos) return;
    const openvdb::Vec3d s = parseRawSpacing(text.substr(cut + 1));
    require(s.x() > 0 && s.y() > 0 && s.z() > 0, "positive spacing", text);
}

inline Outcome textParsers(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return {false, "", true};
    const std::string text(asText(data + 1, size - 1));
    return guarded([&] {
        switch (data[0] % 7) {
            case 0: frameRange(text); break;
            case 1: frameName(text); break;
            case 2: tiles(text); break;
            case 3: resolution(text); break;
            case 4: renderRequest(text); break;
            case 5: techniqueParams(text); break;
            default: rawOptions(text); break;
        }
    });
}

}  // namespace weft::fuzz
