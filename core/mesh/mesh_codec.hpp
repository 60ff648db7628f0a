#pragma once
// PLY files are read by Assimp, kept in a module of its own (weft_assimp.so
// beside the executable, loaded the first time a PLY is read): Assimp's
// symbols cost every weft process about 6 ms at start-up, and most scenes
// have no PLY. Plain std types cross the boundary, so the module needs no
// weft type.
#include <string>
#include <vector>

namespace weft {

struct MeshCodec {
    int abiVersion;
    // Reads every polygon of a PLY: xyz per vertex, the vertex count of each
    // face and their indices, concatenated (points and lines dropped).
    // Returns "" or what went wrong (the library's words, perhaps on several lines).
    std::string (*readPly)(const std::string& path, std::vector<float>& xyz, std::vector<int>& faceSizes,
                           std::vector<int>& faceIndices);
};

constexpr int kMeshCodecAbi = 1;

// The module, loaded once (thread-safe); a weft::Error names the paths tried.
const MeshCodec& meshCodec();

}  // namespace weft

// The module's one entry point.
extern "C" const void* weft_mesh_codec();  // the module's MeshCodec
