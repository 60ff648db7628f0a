// The mesh codec module (weft_assimp.so): Assimp's PLY reader behind
// core/mesh/mesh_codec.hpp, so that only processes that read a PLY load it.
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <exception>
#include <new>

#include "core/mesh/mesh_codec.hpp"

namespace {

std::string readPolygons(const std::string& path, std::vector<float>& xyz, std::vector<int>& faceSizes, std::vector<int>& faceIndices) {
    Assimp::Importer importer;
    // Validation runs before the other steps: joining vertices indexes them by
    // the file's face indices unchecked, and crashed on one out of range.
    const aiScene* scene = importer.ReadFile(path, aiProcess_ValidateDataStructure | aiProcess_JoinIdenticalVertices);
    if (!scene) return importer.GetErrorString();
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh& mesh = *scene->mMeshes[m];
        const int base = int(xyz.size() / 3);
        for (unsigned i = 0; i < mesh.mNumVertices; ++i) xyz.insert(xyz.end(), {mesh.mVertices[i].x, mesh.mVertices[i].y, mesh.mVertices[i].z});
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices < 3) continue;  // points and lines carry no surface
            for (unsigned k = 0; k < face.mNumIndices; ++k) faceIndices.push_back(base + int(face.mIndices[k]));
            faceSizes.push_back(int(face.mNumIndices));
        }
    }
    return "";
}

// No exception crosses the module's boundary.
std::string readPly(const std::string& path, std::vector<float>& xyz, std::vector<int>& faceSizes, std::vector<int>& faceIndices) {
    try {
        return readPolygons(path, xyz, faceSizes, faceIndices);
    } catch (const std::bad_alloc&) {
        return "not enough memory to read it";
    } catch (const std::exception& e) {
        return e.what();
    }
}

const weft::MeshCodec kCodec{weft::kMeshCodecAbi, readPly};

}  // namespace

// `const void*`, the type loadModule calls it through (core/base/files/module_loader.hpp).
extern "C" const void* weft_mesh_codec() { return &kCodec; }
