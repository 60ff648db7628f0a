#pragma once
// One value checked against its declaration: the single rule behind a
// technique's parameters (ParamTable::parse) and the render options' table
// (render_options.cpp). Each words its own errors from the fault.
#include <string>

#include "core/base/options/params.hpp"

namespace weft {

struct ParamValue {
    enum class Fault { None, NotBool, NotNumber, NotInteger, OutOfRange, NotChoice, Check };
    Fault fault = Fault::None;
    double number = 0;       // Int and Float values; 1/0 for Bool
    std::string canonical;   // the value as recorded ("true", "16", "0.5")
    std::string checkMessage;  // a String's own check, in its words (Fault::Check)
};

// Numbers are plain decimal or exponent notation (no hex, no sign '+', no
// blanks), finite; an Int is whole and within its range exactly, however
// large (integerOutOfRange).
ParamValue checkParamValue(const ParamSpec& spec, const std::string& text);

}  // namespace weft
