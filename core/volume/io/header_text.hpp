#pragma once
// Text helpers shared by the option parsers and the volume header readers
// (NRRD, NumPy, VTK): splitting and whole-field numbers (quoteValue, for
// error messages, is core/base/quote_value.hpp).
#include <charconv>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/quote_value.hpp"

namespace weft {

std::vector<std::string> splitOn(std::string_view text, char separator);
// Fields separated by runs of spaces, tabs, CR or LF; none are empty.
std::vector<std::string_view> splitWhitespace(std::string_view text);
std::string_view trimSpace(std::string_view text);
std::string lowerAscii(std::string_view text);
bool endsWithText(std::string_view text, std::string_view suffix);

// from_chars wants the whole field: "12abc" or " 12" are not numbers.
template <class T>
bool parseWhole(std::string_view field, T& value) {
    const char* end = field.data() + field.size();
    const auto [ptr, ec] = std::from_chars(field.data(), end, value);
    return !field.empty() && ec == std::errc() && ptr == end;
}

// A finite number ("nan", "inf" and overflow are not).
bool parseFinite(std::string_view field, double& value);

}  // namespace weft
