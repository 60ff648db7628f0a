#pragma once
// Sampling-distance oracles for adaptive volume integration (Kraus et al.
// 2007). An oracle answers, for any point, how far apart samples may be
// there without missing a feature. Each oracle is one .cpp file in this
// folder that registers a builder by name; the builder precomputes a field
// once per volume and transfer function, which renderers then sample at the
// same points as the data (no virtual call per sample).
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <openvdb/openvdb.h>
#include <openvdb/tree/ValueAccessor.h>

#include "core/base/registry.hpp"
#include "core/volume/volume.hpp"

namespace weft {

struct OracleContext {
    const Volume& volume;
    double sliceSpacing;  // the minimum sampling distance, in voxels
    int lmax;             // distances are useful up to 2^lmax slices
    double epsilon;       // feature threshold (meaning depends on the oracle)
};

// A precomputed field holds few distinct distances (one per ring of voxels
// around its features), so each voxel stores the index of its distance, one
// byte, in a tree of the volume's index space: a quarter of a float tree's
// memory, whose first touches dominated building the field.
using RingTree = openvdb::tree::Tree4<std::uint8_t, 5, 4, 3>::Type;
using RingAccessor = openvdb::tree::ValueAccessor<const RingTree>;
constexpr std::uint8_t kFarRing = 255;  // the trees' background: beyond every stored ring

// Sampling distances in voxels, in the volume's index space: a tree of
// distance indices, or one constant everywhere. Values are never below
// ctx.sliceSpacing; renderers clamp to 2^lmax slices.
struct OracleField {
    std::shared_ptr<const RingTree> rings;  // null when constant
    std::vector<float> distances;           // 256 entries when `rings` is set
    float constant = 1.0f;                  // used when rings is null
    // The tree's voxel v + shift holds the distance at the volume's voxel v
    // (whole leaves: see oracleShift in oracles/feature_distance.hpp).
    openvdb::Coord shift{0};

    // An accessor for at(): of the rings, or of an empty tree when constant.
    RingAccessor accessor() const;
    // The distance beyond the stored rings.
    float background() const { return rings ? distances[kFarRing] : constant; }

    // Distance at an index-space point of the volume (nearest-voxel lookup).
    [[gnu::always_inline]] float at(const RingAccessor& acc, const openvdb::Vec3d& indexPos) const {
        if (!rings) return constant;
        // Beyond int range (or NaN) a Coord cannot be formed; the tree's
        // background is what it holds there.
        constexpr double kFar = double(1 << 30);
        const openvdb::Vec3d p = indexPos + shift.asVec3d();
        if (!(std::abs(p.x()) < kFar && std::abs(p.y()) < kFar && std::abs(p.z()) < kFar)) return distances[kFarRing];
        return distances[acc.getValue(openvdb::Coord::round(p))];
    }

    // Distance at one of the volume's voxels.
    float atVoxel(const openvdb::Coord& voxel) const { return rings ? distances[rings->getValue(voxel + shift)] : constant; }
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
