#pragma once
// weft's one exception type. Its message is a complete, user-facing sentence
// naming what was wrong and where; the host prints it on one line.
#include <stdexcept>
#include <string>

namespace weft {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace weft
