#include "core/image/image_codec.hpp"

#include <mutex>

#include "core/base/error.hpp"
#include "core/base/module_loader.hpp"

namespace weft {

namespace {

// WEFT_IMAGE_CODEC if set, else weft_oiio.so beside the executable (core/base/module_loader.hpp).
const ImageCodec* load() {
    return static_cast<const ImageCodec*>(loadModule("weft_oiio.so", "WEFT_IMAGE_CODEC", "weft_image_codec", [](const void* m) {
        return static_cast<const ImageCodec*>(m)->abiVersion == kImageCodecAbi;
    }));
}

}  // namespace

const ImageCodec& imageCodec() {
    static std::once_flag once;
    static const ImageCodec* codec = nullptr;
    static std::string failure;
    std::call_once(once, [] {
        try {
            codec = load();
        } catch (const Error& e) {
            failure = e.what();
        }
    });
    if (!codec) throw Error(failure);
    return *codec;
}

}  // namespace weft
