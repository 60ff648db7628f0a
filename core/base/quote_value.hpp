#pragma once
// Values of the input quoted in error messages, shortened so that a hostile
// file (a number of 400 digits, a header line of a megabyte) cannot flood a
// terminal.
#include <string>
#include <string_view>

namespace weft {

// 'value', or its first 60 characters: '...' (N characters).
std::string quoteValue(std::string_view value);

}  // namespace weft
