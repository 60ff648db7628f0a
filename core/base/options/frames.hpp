#pragma once
// Frame ranges and frame-numbered file names, as oiiotool writes them, and
// the row bands a frame is split into for tiled farm renders.
//
// Ranges: comma-separated items, each a frame "7", a span "1001-1100" or a
// stepped span "1001-1100x2"; frames may be negative ("-5--1", "-3-2");
// a span whose end is below its start counts down. Frames keep the order
// given; a frame listed twice is an error.
//
// Names: the first run of '#' and '@' characters in a name is the frame
// number, each '#' standing for 4 digits and each '@' for 1 digit of zero
// padding (oiiotool's rule: "#" -> 0042, "@@@" -> 042, "####" -> 16 digits).
// "%0Nd" (or "%d") is accepted too. The sign of a negative frame counts in
// the width, like printf: "#" with -5 -> -005.
#include <optional>
#include <string>
#include <vector>

namespace weft {

// Frames of a range text, in order; a malformed text is an Error naming it.
std::vector<int> parseFrameRange(const std::string& text);

// Whether a name holds a frame-number wildcard.
bool hasFrameWildcard(const std::string& name);

// The name with its wildcard replaced by the frame; names without one are
// returned unchanged.
std::string expandFrameName(const std::string& name, int frame);

// The rows [begin, end) of tile `index` (1-based) of `count` horizontal
// bands over an image `height` rows high. Bands differ by at most one row,
// so any count up to the height works, whether it divides it or not.
struct RowBand {
    int begin = 0;
    int end = 0;
};
RowBand tileRows(int height, int index, int count);

// Tile `index` (1-based) of `count` row bands, valid when 1 <= index <= count <= 65536.
struct TileSpec {
    int index = 1;
    int count = 1;

    bool valid() const;
    std::string text() const;  // "i/n"
    bool operator==(const TileSpec&) const = default;
};
// "i/n" -> {i, n}, valid; anything else is an Error naming the text.
TileSpec parseTileSpec(const std::string& text);
// A tile built in code, held to the same limits and error as parseTileSpec.
void requireValid(const TileSpec& tile);

}  // namespace weft
