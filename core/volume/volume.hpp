#pragma once
// A volume in a scene: an OpenVDB float grid plus its transfer function.
// Grids come from .vdb files or from the procedural generators below.
#include <memory>
#include <string>

#include <openvdb/openvdb.h>

#include "core/scene/camera.hpp"
#include "core/volume/transfer_function.hpp"

namespace weft {

struct Volume {
    std::string name;    // grid name
    std::string source;  // file path or "procedural:<kind>"
    openvdb::FloatGrid::ConstPtr grid;
    TransferFunction tf;
    float valueMin = 0, valueMax = 0;      // over active values
    openvdb::CoordBBox activeBox;          // active voxels' bounding box

    // Index-space box that holds every voxel whose value can be non-zero,
    // padded by one voxel for trilinear support.
    openvdb::CoordBBox indexBox() const;
    BBoxd worldBox() const;
};

// Calls openvdb::initialize() once.
void initVdb();

// Reads one float grid. gridName empty: "density" if present, else the first
// float grid. Errors name the file and list the grids it holds.
openvdb::FloatGrid::Ptr readFloatGrid(const std::string& path, const std::string& gridName);

// Fills the value range and the active bounding box (once per volume: both
// walk the whole tree).
void computeStatistics(Volume& volume);

// Procedural grids (deterministic), sized res^3 voxels, voxel size 1/res so
// the object fills the unit cube [-0.5, 0.5]^3 in world space:
//   "sphere": constant density 1 inside radius 0.4 (closed-form transmittance)
//   "cloud":  a sphere displaced and modulated by fractal value noise
openvdb::FloatGrid::Ptr makeProceduralGrid(const std::string& kind, int res, std::uint64_t seed);
const char* proceduralKinds();  // "sphere|cloud", for error messages

}  // namespace weft
