#include "core/mesh/mesh_codec.hpp"

#include "core/base/files/module_loader.hpp"

namespace weft {

const MeshCodec& meshCodec() {
    return moduleCodec<MeshCodec>("weft_assimp.so", "WEFT_MESH_CODEC", "weft_mesh_codec", kMeshCodecAbi);
}

}  // namespace weft
