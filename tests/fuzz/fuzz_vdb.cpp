// libFuzzer entry point; the target is vdb_target.hpp (shared with the regression tests).
#include "tests/fuzz/vdb_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    weft::fuzz::vdbFile(data, size);
    return 0;
}
