// libFuzzer entry point; the target is exr_target.hpp (shared with the regression tests).
#include "tests/fuzz/exr_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    weft::fuzz::exrFile(data, size);
    return 0;
}
