#pragma once
// weft's one exception type. Its message is a complete, user-facing sentence
// naming what was wrong and where; the host prints it on one line.
#include <stdexcept>
#include <string>
#include <string_view>

namespace weft {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A message as one printable line: newlines and tabs become spaces, control
// bytes and bytes that are not UTF-8 (raw file contents inside a library's
// message) become \xNN.
std::string printableLine(std::string_view text);

}  // namespace weft
