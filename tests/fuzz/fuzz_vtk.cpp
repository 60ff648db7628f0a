// libFuzzer entry point; the target is volume_file_target.hpp (shared with the regression tests).
#include "tests/fuzz/volume_file_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    weft::fuzz::vtkVolume(data, size);
    return 0;
}
