// libFuzzer entry point; the target is text_parsers_target.hpp (shared with the regression tests).
#include "tests/fuzz/text_parsers_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    weft::fuzz::textParsers(data, size);
    return 0;
}
