// libFuzzer entry point; the target is raw_target.hpp (shared with the regression tests).
#include "tests/fuzz/raw_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    weft::fuzz::rawVolume(data, size);
    return 0;
}
