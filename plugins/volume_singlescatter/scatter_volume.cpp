#include "plugins/volume_singlescatter/scatter_volume.hpp"

#include <algorithm>
#include <cmath>

#include "core/volume/grid/octant_shift.hpp"
#include "plugins/volume_singlescatter/shared_caches.hpp"

namespace weft {

namespace {

// The active voxels of `occupancy` (an index-space grid) shifted by `shift`.
openvdb::MaskGrid::Ptr shiftedOccupancy(const openvdb::FloatGrid& occupancy, const openvdb::Coord& shift) {
    openvdb::MaskGrid::Ptr mask = shiftedMask(occupancy.transform(), shift);
    addShiftedTopology(occupancy.tree(), shift, mask->tree());
    return mask;
}

// Whether any ray marches the intersector's spans: camera rays without
// reaching blocks, and shadow rays (traced estimators, moving volumes,
// emissive triangles, which the cache does not hold).
bool marchesSpans(const ScatterVolume& v, const ScatterParams& params, const Scene& scene) {
    return !v.reaching || params.estimator != ShadowEstimator::Cached || params.emitters || scene.volumesMove();
}

void setCoefficients(ScatterVolume& v, const Vec3d& absorb, const Vec3d& scatter) {
    v.sigmaT = absorb + scatter;
    for (int c = 0; c < 3; ++c) v.albedo[c] = v.sigmaT[c] > 0 ? scatter[c] / v.sigmaT[c] : 0.0;
}

}  // namespace

openvdb::CoordBBox shiftedNodeBox(const openvdb::FloatTree& tree, const openvdb::Coord& shift) {
    openvdb::CoordBBox box;
    tree.root().evalActiveBoundingBox(box, /*visitVoxels=*/false);
    box.translate(shift);
    box.max().offset(1);
    return box;
}

std::vector<ScatterVolume> scatterVolumes(const Scene& scene, const ScatterParams& params, bool paramsWin) {
    std::vector<ScatterVolume> out;
    for (const Volume& vol : scene.volumes) {
        if (vol.empty()) continue;  // OpenVDB's intersector refuses empty grids; they add nothing
        ScatterVolume v;
        v.volume = &vol;
        if (!vol.emission && !vol.motion)
            v.reaching = sharedReaching(vol, float(params.cutoff), VisibleBlocks::Within::ActiveBlocks);
        // Shifted by whole leaves to lie a leaf above the origin on every axis.
        const openvdb::FloatGrid::ConstPtr occupied = occupancyIndexGrid(vol);
        const openvdb::Coord shift = -widthBelow(occupied->evalActiveVoxelBoundingBox(), 8);
        v.shift = shift.asVec3d();
        if (marchesSpans(v, params, scene)) {
            v.occupancy = shiftedOccupancy(*occupied, shift);
            v.intersector = std::make_shared<const VdbIntersector>(*v.occupancy);
            v.occupancyBox = v.intersector->bbox();
        } else {
            v.occupancyBox = shiftedNodeBox(occupied->tree(), shift);
        }
        v.phase = params.phase, v.g = params.g;
        if (vol.medium.fromScene && !paramsWin) {
            setCoefficients(v, vol.medium.absorb, vol.medium.scatter);
            if (vol.medium.g != 0) v.phase = Phase::HenyeyGreenstein, v.g = vol.medium.g;
        } else {
            setCoefficients(v, params.absorb, params.scatter);
        }
        v.majorantDensity = std::max(std::abs(vol.valueMin), std::abs(vol.valueMax));
        v.voxelLength = vol.voxelLength();
        v.uniform = vol.grid->transform().hasUniformScale();
        v.map = vol.grid->transform().baseMap().get();
        out.push_back(std::move(v));
    }
    return out;
}

}  // namespace weft
