// libFuzzer entry point; the target is scene_json_target.hpp (shared with the regression tests).
#include "tests/fuzz/scene_json_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    weft::fuzz::sceneJson(data, size);
    return 0;
}
