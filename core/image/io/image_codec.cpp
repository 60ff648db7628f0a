#include "core/image/io/image_codec.hpp"

#include "core/base/files/module_loader.hpp"

namespace weft {

const ImageCodec& imageCodec() {
    return moduleCodec<ImageCodec>("weft_oiio.so", "WEFT_IMAGE_CODEC", "weft_image_codec", kImageCodecAbi);
}

}  // namespace weft
