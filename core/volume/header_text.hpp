#pragma once
// Text helpers shared by the option parsers and the volume header readers
// (NRRD, NumPy, VTK): splitting, whole-field numbers, and values quoted for
// error messages (shortened, so a hostile header cannot flood a terminal).
#include <charconv>
#include <string>
#include <string_view>
#include <vector>

namespace weft {

std::vector<std::string> splitOn(std::string_view text, char separator);
// Fields separated by runs of spaces, tabs, CR or LF; none are empty.
std::vector<std::string_view> splitWhitespace(std::string_view text);
std::string_view trimSpace(std::string_view text);
std::string lowerAscii(std::string_view text);
bool endsWithText(std::string_view text, std::string_view suffix);

// 'value' for a message, at most 60 characters of it.
std::string quoteValue(std::string_view value);

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
