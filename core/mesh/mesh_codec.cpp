#include "core/mesh/mesh_codec.hpp"

#include <mutex>

#include "core/base/error.hpp"
#include "core/base/module_loader.hpp"

namespace weft {

const MeshCodec& meshCodec() {
    static std::once_flag once;
    static const MeshCodec* codec = nullptr;
    static std::string failure;
    std::call_once(once, [] {
        try {
            codec = static_cast<const MeshCodec*>(loadModule("weft_assimp.so", "WEFT_MESH_CODEC", "weft_mesh_codec", [](const void* m) {
                return static_cast<const MeshCodec*>(m)->abiVersion == kMeshCodecAbi;
            }));
        } catch (const Error& e) {
            failure = e.what();
        }
    });
    if (!codec) throw Error(failure);
    return *codec;
}

}  // namespace weft
