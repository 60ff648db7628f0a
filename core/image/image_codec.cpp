#include "core/image/image_codec.hpp"

#include "core/base/module_loader.hpp"

namespace weft {

const ImageCodec& imageCodec() {
    return moduleCodec<ImageCodec>("weft_oiio.so", "WEFT_IMAGE_CODEC", "weft_image_codec", kImageCodecAbi);
}

}  // namespace weft
