// libFuzzer entry point; the target is mesh_target.hpp (shared with the regression tests).
#include "tests/fuzz/mesh_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    weft::fuzz::objFile(data, size);
    return 0;
}
