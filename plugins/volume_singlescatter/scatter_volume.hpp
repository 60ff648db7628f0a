#pragma once
// What volume.singlescatter keeps of each volume for one render: its
// coefficients (the scene's medium, else the technique's absorb/scatter),
// an OpenVDB intersector on its index-space copy (the intersector needs
// uniform voxels; index-space rays work for any affine transform), and the
// lengths that turn index units into voxel lengths.
#include <openvdb/tools/RayIntersector.h>

#include <memory>
#include <vector>

#include "core/scene/scene.hpp"
#include "plugins/volume_singlescatter/scatter_params.hpp"

namespace weft {

using VdbIntersector = openvdb::tools::VolumeRayIntersector<openvdb::FloatGrid>;
using VdbRay = VdbIntersector::RayType;

struct ScatterVolume {
    const Volume* volume = nullptr;
    openvdb::FloatGrid::ConstPtr indexGrid;       // the intersector points into it
    std::shared_ptr<const VdbIntersector> intersector;
    Vec3d sigmaT, albedo;                         // per voxel length per unit density
    Phase phase = Phase::Isotropic;
    double g = 0;
    double majorantDensity = 0;                   // bounds |density|
    double voxelLength = 1;
    bool uniform = true;                          // index units are voxel lengths exactly
    const openvdb::math::MapBase* map = nullptr;  // the grid's index-to-world map (no shared_ptr copies per ray)

    // The world ray in index space, as OpenVDB's worldToIndex maps it (t
    // counts voxels), through the map itself: no shared_ptr copy per ray.
    VdbRay indexRay(const VdbRay& world) const { return world.applyInverseMap(*map); }
    // Voxel lengths per index unit along a unit index-space direction (1 on uniform grids).
    double voxelLengthsPerIndexUnit(const Vec3d& indexDir) const {
        if (uniform) return 1.0;
        return map->applyJacobian(indexDir).length() / voxelLength;
    }
    // Index units per unit of a world ray's parameter.
    double indexSpeed(const Vec3d& worldDir) const { return map->applyInverseJacobian(worldDir).length(); }
    Vec3d worldPos(const VdbRay& indexRay, double t) const { return volume->grid->indexToWorld(indexRay(t)); }
};

// The scene's non-empty volumes. A scene's medium wins unless absorb or
// scatter are set on the technique.
std::vector<ScatterVolume> scatterVolumes(const Scene& scene, const ScatterParams& params, bool paramsWin);

}  // namespace weft
