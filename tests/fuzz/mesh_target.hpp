#pragma once
// Fuzz targets: .obj (with an optional .mtl) and .ply mesh files
// (core/mesh/mesh_io.cpp), as a bare mesh input and as a scene's mesh with
// subdivision, so the triangulation and OpenSubdiv see what the readers
// accept.
#include <cmath>

#include "core/mesh/mesh.hpp"
#include "core/scene/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace weft::fuzz {

// Whatever a reader accepts, the triangles refer to existing vertices and
// every position is finite (Embree aborts on anything else).
inline void checkTriangles(const TriangleMesh& m, std::size_t materialCount) {
    require(m.indices.size() % 3 == 0, "whole triangles");
    require(m.material.size() == m.triangleCount(), "one material per triangle");
    for (std::uint32_t i : m.indices) require(i < m.positions.size(), "triangle index in range");
    for (std::uint32_t i : m.material) require(i < materialCount, "material index in range");
    for (const Vec3f& p : m.positions)
        require(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()), "finite positions");
}

inline void meshThroughWeft(const std::string& path) {
    const PolyMesh poly = readPolyMesh(path);
    const TriangleMesh triangles = triangulate(poly, path);
    checkTriangles(triangles, triangles.materials.size());
    // Subdivision cost grows with the face count; one level shows what
    // OpenSubdiv makes of the topology.
    if (poly.faceCount() <= 256) {
        const TriangleMesh refined = subdivide(poly, 1, path);
        checkTriangles(refined, refined.materials.size());
    }
    const Scene scene = loadScene(path);
    for (const TriangleMesh& m : scene.meshes) checkTriangles(m, scene.materials.size());
}

// The OBJ input is the .obj text, optionally followed by a line "#MTL" and
// the text of fuzz.mtl, which the .obj may name with `mtllib fuzz.mtl`.
inline Outcome objFile(const std::uint8_t* data, std::size_t size) {
    const std::string_view text = asText(data, size);
    const std::size_t cut = text.find("\n#MTL\n");
    writeScratch("fuzz.mtl", cut == std::string_view::npos ? std::string_view() : text.substr(cut + 6));
    const std::string path = writeScratch("mesh.obj", text.substr(0, cut));
    return guarded([&] { meshThroughWeft(path); });
}

inline Outcome plyFile(const std::uint8_t* data, std::size_t size) {
    const std::string path = writeScratch("mesh.ply", asText(data, size));
    return guarded([&] { meshThroughWeft(path); });
}

}  // namespace weft::fuzz
