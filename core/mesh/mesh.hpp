#pragma once
// Meshes: polygon meshes as files give them (faces of any size, creases for
// subdivision) and the triangle meshes the ray tracer and techniques use.
// Materials follow the OBJ/MTL model: diffuse Kd, glossy Ks with Phong
// exponent Ns, emission Ke (one-sided, on the side the winding faces).
#include <cstdint>
#include <string>
#include <vector>

#include <openvdb/math/Mat4.h>

#include "core/scene/camera.hpp"

namespace weft {

struct Material {
    std::string name = "default";
    Vec3f diffuse{0.8f, 0.8f, 0.8f};  // Kd, albedo of the Lambertian lobe
    Vec3f glossy{0, 0, 0};            // Ks, albedo of the Phong lobe
    float exponent = 1.0f;            // Ns, Phong exponent
    Vec3f emission{0, 0, 0};          // Ke, radiance leaving the front face

    bool emissive() const { return emission.x() > 0 || emission.y() > 0 || emission.z() > 0; }
    bool hasGlossy() const { return glossy.x() > 0 || glossy.y() > 0 || glossy.z() > 0; }
};

// A sharp edge between two control vertices, as OBJ `t crease` tags give it.
struct Crease {
    int v0 = 0, v1 = 0;
    float sharpness = 0;
};

// A mesh as read from a file, before triangulation or subdivision.
struct PolyMesh {
    std::vector<Vec3f> positions;
    std::vector<int> faceSizes;    // vertices per face
    std::vector<int> faceIndices;  // concatenated vertex indices of every face
    std::vector<int> faceMaterial; // material per face (index into materials)
    std::vector<Material> materials;
    std::vector<Crease> creases;
    std::vector<std::pair<int, float>> corners;  // vertex, sharpness

    int faceCount() const { return int(faceSizes.size()); }
};

// Triangles with one material each; what the renderer consumes.
struct TriangleMesh {
    std::string source;
    std::vector<Vec3f> positions;
    std::vector<std::uint32_t> indices;   // 3 per triangle
    std::vector<std::uint32_t> material;  // per triangle, index into materials
    std::vector<Material> materials;

    std::size_t triangleCount() const { return indices.size() / 3; }
    BBoxd bounds() const;
};

// Fan-triangulates every face (convex polygons, as OBJ/PLY files hold them).
TriangleMesh triangulate(const PolyMesh& mesh, const std::string& source);

// Catmull-Clark refinement (OpenSubdiv Far, creases and corners honoured) to
// `level` uniform levels, then triangulated. Level 0 triangulates the cage.
TriangleMesh subdivide(const PolyMesh& mesh, int level, const std::string& source);

// Reads .obj (with its .mtl; tinyobjloader) or .ply (Assimp). Errors are one
// line naming the file and what is wrong with it.
PolyMesh readPolyMesh(const std::string& path);

// Moves every position by an object-to-world map (core/scene/placement.hpp).
void transformMesh(PolyMesh& mesh, const openvdb::math::Mat4d& objectToWorld);

}  // namespace weft
