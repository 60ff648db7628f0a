#pragma once
// Files the extremes suite renders: small VDB grids of chosen values and
// transforms, OBJ meshes written as text, and scene JSON around them.
#include <openvdb/io/File.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "core/volume/volume.hpp"
#include "tests/support/test_support.hpp"

namespace weft::test::extremes {

using nlohmann::json;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// An n^3 grid of voxels (0..n-1 on each axis), each set active to value(i, j, k)
// unless that is exactly 0, under `xf` (default: voxel size 1/n).
inline void writeGrid(const std::filesystem::path& path, int n, const std::function<float(int, int, int)>& value,
                      openvdb::math::Transform::Ptr xf = nullptr) {
    initVdb();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setTransform(xf ? xf : openvdb::math::Transform::createLinearTransform(1.0 / n));
    auto acc = grid->getAccessor();
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k)
                if (const float v = value(i, j, k); v != 0.0f) acc.setValue(openvdb::Coord(i, j, k), v);
    openvdb::io::File file(path.string());
    file.write({grid});
    file.close();
}

inline void writeConstantGrid(const std::filesystem::path& path, int n, float v, openvdb::math::Transform::Ptr xf = nullptr) {
    writeGrid(path, n, [v](int, int, int) { return v; }, std::move(xf));
}

// A transform from a 4x4 matrix (row vectors, OpenVDB's convention): anisotropic,
// rotated and sheared grids.
inline openvdb::math::Transform::Ptr affine(const openvdb::math::Mat4d& m) {
    return openvdb::math::Transform::createLinearTransform(m);
}

// A unit quad at height y facing up, and a closed cube, as OBJ text.
inline std::string groundObj(double half, double y) {
    const std::string h = std::to_string(half), hy = std::to_string(y);
    return "v -" + h + " " + hy + " -" + h + "\nv " + h + " " + hy + " -" + h + "\nv " + h + " " + hy + " " + h + "\nv -" + h +
           " " + hy + " " + h + "\nf 1 3 2\nf 1 4 3\n";
}

inline std::string cubeObj(double half) {
    std::string s;
    for (int i = 0; i < 8; ++i)
        s += "v " + std::to_string(i & 1 ? half : -half) + " " + std::to_string(i & 2 ? half : -half) + " " +
             std::to_string(i & 4 ? half : -half) + "\n";
    // Each face as two triangles (vertex indices are 1-based).
    const char* faces = "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";
    return s + faces;
}

inline json directionalLight(double intensity = 1.0) {
    return {{"type", "directional"}, {"direction", {0.3, -1.0, 0.2}}, {"intensity", intensity}};
}

inline json pointLight(const std::array<double, 3>& at, double intensity) {
    return {{"type", "point"}, {"position", {at[0], at[1], at[2]}}, {"intensity", intensity}};
}

inline json camera(const std::array<double, 3>& eye, const std::array<double, 3>& target, double fov = 40) {
    return {{"eye", {eye[0], eye[1], eye[2]}}, {"target", {target[0], target[1], target[2]}}, {"fov", fov}};
}

}  // namespace weft::test::extremes
