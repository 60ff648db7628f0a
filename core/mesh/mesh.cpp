#include "core/mesh/mesh.hpp"

#include "core/base/error.hpp"

namespace weft {

BBoxd TriangleMesh::bounds() const {
    BBoxd box;
    for (const Vec3f& p : positions) box.expand(Vec3d(p.x(), p.y(), p.z()));
    return box;
}

TriangleMesh triangulate(const PolyMesh& mesh, const std::string& source) {
    TriangleMesh out;
    out.source = source;
    out.positions = mesh.positions;
    out.materials = mesh.materials;
    std::size_t first = 0;
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int n = mesh.faceSizes[f];
        for (int k = 1; k + 1 < n; ++k) {
            out.indices.push_back(std::uint32_t(mesh.faceIndices[first]));
            out.indices.push_back(std::uint32_t(mesh.faceIndices[first + k]));
            out.indices.push_back(std::uint32_t(mesh.faceIndices[first + k + 1]));
            out.material.push_back(std::uint32_t(mesh.faceMaterial[f]));
        }
        first += std::size_t(n);
    }
    return out;
}

void transformMesh(PolyMesh& mesh, const openvdb::math::Mat4d& objectToWorld) {
    for (Vec3f& p : mesh.positions) {
        p = toVec3f(objectToWorld.transform(toVec3d(p)));
    }
}

}  // namespace weft
