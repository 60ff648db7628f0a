#pragma once
// Sampling-distance oracles for adaptive volume integration (Kraus et al.
// 2007). An oracle answers, for any point, how far apart samples may be
// there without missing a feature. Each oracle is one .cpp file in this
// folder that registers a builder by name; the builder precomputes a field
// once per volume and transfer function, which renderers then sample at the
// same points as the data (no virtual call per sample).
#include <cmath>
#include <functional>
#include <string>

#include <openvdb/openvdb.h>

#include "core/base/registry.hpp"
#include "core/volume/volume.hpp"

namespace weft {

struct OracleContext {
    const Volume& volume;
    double sliceSpacing;  // the minimum sampling distance, in voxels
    int lmax;             // distances are useful up to 2^lmax slices
    double epsilon;       // feature threshold (meaning depends on the oracle)
};

// Sampling distances in voxels, in the volume's index space: a grid sharing
// the volume's transform, or one constant everywhere. Values are never
// below ctx.sliceSpacing; renderers clamp to 2^lmax slices.
struct OracleField {
    openvdb::FloatGrid::ConstPtr distance;  // null when constant
    float constant = 1.0f;                  // used when distance is null
    // The grid's voxel v + shift holds the distance at the volume's voxel v
    // (whole leaves: see oracleShift in oracles/feature_distance.hpp).
    openvdb::Coord shift{0};

    // Distance at an index-space point of the volume (nearest-voxel lookup),
    // through an accessor of `distance`.
    template <class Accessor>
    float at(const Accessor& acc, const openvdb::Vec3d& indexPos) const {
        if (!distance) return constant;
        // Beyond int range (or NaN) a Coord cannot be formed; the grid's
        // background is what it holds there.
        constexpr double kFar = double(1 << 30);
        const openvdb::Vec3d p = indexPos + shift.asVec3d();
        if (!(std::abs(p.x()) < kFar && std::abs(p.y()) < kFar && std::abs(p.z()) < kFar)) return distance->background();
        return acc.getValue(openvdb::Coord::round(p));
    }

    // Distance at one of the volume's voxels.
    float atVoxel(const openvdb::Coord& voxel) const { return distance ? distance->tree().getValue(voxel + shift) : constant; }
};

// The field of a volume whose data move by up to `reach` voxels while the
// shutter is open (velocity motion blur: Volume::motionReach). Every
// precomputed oracle's distance grows by at most one voxel per voxel
// (oracles/feature_distance.hpp), and a feature moved by up to reach is at
// most reach nearer, so each distance shrinks by the reach, never below
// minDistance (one slice). A field that does not move is handed back as it is.
OracleField paddedByReach(const OracleField& field, double reach, double minDistance);

struct OracleInfo {
    std::string name;
    std::string summary;
    std::function<OracleField(const OracleContext&)> build;
};

using OracleRegistry = NamedRegistry<OracleInfo>;
OracleRegistry& oracles();

struct OracleRegistrar {
    explicit OracleRegistrar(OracleInfo info) { oracles().add(std::move(info)); }
};

}  // namespace weft
