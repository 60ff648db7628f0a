#pragma once
// Small in-memory volumes for the medium, transmittance, ray and slice tests.
#include "core/volume/volume.hpp"

namespace weft::test {

// A cube of res^3 voxels of size 1/res (world [0, 1)^3), density from f.
template <class Density>
Volume cubeVolume(int res, const Vec3d& absorb, const Vec3d& scatter, const Density& f) {
    initVdb();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(1.0 / res));
    auto acc = grid->getAccessor();
    for (int i = 0; i < res; ++i)
        for (int j = 0; j < res; ++j)
            for (int k = 0; k < res; ++k) acc.setValue(openvdb::Coord(i, j, k), f(i, j, k));
    Volume v;
    v.grid = grid;
    v.medium.absorb = absorb, v.medium.scatter = scatter;
    computeStatistics(v);
    return v;
}

// Sheared, anisotropic and moved away from the origin, with data in one corner.
inline Volume skewedVolume() {
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(
        openvdb::math::Mat4d(0.5, 0.1, 0.0, 0.0, 0.0, 0.25, 0.05, 0.0, 0.2, 0.0, 0.7, 0.0, 1.0, -2.0, 3.0, 1.0)));
    grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(-5, 2, 0), openvdb::Coord(20, 17, 11)), 1.0f, true);
    grid->tree().voxelizeActiveTiles();
    Volume v;
    v.grid = grid;
    computeStatistics(v);
    return v;
}

}  // namespace weft::test
