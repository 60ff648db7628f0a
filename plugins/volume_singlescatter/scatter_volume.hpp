#pragma once
// What volume.singlescatter keeps of each volume for one render: its
// coefficients (the scene's medium, else the technique's absorb/scatter),
// an OpenVDB intersector on its occupied voxels in index space (the
// intersector needs uniform voxels; index-space rays work for any affine
// transform), and the lengths that turn index units into voxel lengths.
// The intersector's voxels are shifted by whole leaves so that their
// coordinates are positive (core/volume/grid/octant_shift.hpp); rays enter it
// through occupancyRay, shifted alike, and the times along a ray are the same.
// Where nothing marches its spans (camera rays follow the reaching blocks
// and shadows come from the light cache of a still volume), neither the
// shifted occupancy nor the intersector is built: copying the topology
// twice cost 10 ms a frame on the aneurism; only its box is kept.
#include <openvdb/tools/RayIntersector.h>

#include <memory>
#include <vector>

#include "core/scene/scene.hpp"
#include "core/volume/skip/visible_blocks.hpp"
#include "plugins/volume_singlescatter/scatter_params.hpp"

namespace weft {

using VdbIntersector = openvdb::tools::VolumeRayIntersector<openvdb::MaskGrid>;
using VdbRay = VdbIntersector::RayType;

struct ScatterVolume {
    const Volume* volume = nullptr;
    openvdb::MaskGrid::ConstPtr occupancy;        // shifted by `shift`; the intersector points into it
    Vec3d shift{0.0};                             // index point + shift = occupancy point
    std::shared_ptr<const VdbIntersector> intersector;  // null where no ray marches its spans
    // The intersector's box (VolumeRayIntersector::bbox: the shifted nodes
    // that hold active values, its max corner one past), built or not.
    openvdb::CoordBBox occupancyBox;
    // Camera rays march only the cells of the intersector's leaves where a
    // lookup can reach the cutoff (the samples that can add something); null
    // with emission or motion, where the intersector's spans are marched.
    std::shared_ptr<const VisibleBlocks> reaching;
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
    // An index-space ray as the intersector takes it.
    VdbRay occupancyRay(const VdbRay& index) const { return VdbRay(index.eye() + shift, index.dir(), index.t0(), index.t1()); }
    // Whether the intersector's setIndexRay would take this ray (the same clip).
    bool crosses(const VdbRay& occupancy) const {
        VdbRay clipped = occupancy;
        return clipped.clip(occupancyBox);
    }
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

// The box OpenVDB's intersector would hold for an index-space grid's
// active topology shifted by `shift` (whole leaves), without copying it.
openvdb::CoordBBox shiftedNodeBox(const openvdb::FloatTree& tree, const openvdb::Coord& shift);

}  // namespace weft
