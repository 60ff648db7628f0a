#pragma once
// The light cache of volume.singlescatter: for one light, the
// density-weighted path length towards it,
//   D(x) = integral over s of rho(x + s * toLight) / (1 + gain * s) ds,
// at every voxel that trilinear lookups of a non-empty sample can touch.
// Shadow transmittance is then exp(-sigma_t * D(x)) for every colour
// channel, so one march per voxel replaces one march per primary sample
// (vdb_render's cost), and the primary step can shrink without making the
// shadows dearer. Midpoint samples along the march make it second order.
// The cache may be coarser than the density (shadows vary more slowly than
// density), which divides its cost by the cube of the coarsening.
//
// With several volumes a cache lives on a receiving volume's voxels and
// holds one occluding volume's D (the receiver itself or another), so the
// shadow at x is the product over occluders. s and the step are counted in
// the occluder's voxel lengths (cube root of a voxel's volume), which on
// uniform grids are its index units exactly. Meshes on the way to the light
// go into a visibility grid on the receiver's cache voxels (1 lit, 0 blocked).
//
// The march samples only where a lookup of the occluder can reach the
// cutoff (its VisibleBlocks::reaching; null: everywhere), which leaves D
// unchanged: towards the light most of a thin-featured volume's path is
// empty space.
#include <openvdb/openvdb.h>

#include <vector>

#include "core/volume/grid/leaf_sampler.hpp"
#include "core/volume/skip/visible_blocks.hpp"

#include "core/mesh/mesh_accel.hpp"
#include "core/volume/volume.hpp"
#include "plugins/volume_singlescatter/scatter_params.hpp"

namespace weft {

struct LightCacheSettings {
    double step;        // march step, voxel lengths
    double gain;        // vdb_render's gain
    double cutoff;      // densities below it count as empty
    double sigmaMin;    // smallest extinction coefficient (stops the march once T < 1e-4 in every channel)
    int coarsening;     // cache voxels are this many density voxels wide
};

// D of `occluder` for a directional light (toLight in world space) or a
// point light, on the cache voxels of `receiver`.
openvdb::FloatGrid::Ptr buildLightCache(const Volume& receiver, const Volume& occluder, const VisibleBlocks* occluderReaching,
                                        const DirectionalOrPointLight& light, const LightCacheSettings& settings);

// Whether each cache voxel of `receiver` sees the light past the meshes.
openvdb::FloatGrid::Ptr buildVisibilityCache(const Volume& receiver, const MeshAccel& accel,
                                             const DirectionalOrPointLight& light, int coarsening);

// The cache's march from any point (surfaces use it directly): one per
// thread, it holds grid accessors.
class PathMarcher {
public:
    PathMarcher(const Volume& occluder, const VisibleBlocks* reaching, const DirectionalOrPointLight& light,
                const LightCacheSettings& s);
    PathMarcher(const PathMarcher&) = delete;
    // D from x (the occluder's index space) towards the light.
    float densityPath(const Vec3d& x);
    float densityPathFromWorld(const Vec3d& p) { return densityPath(occluder_.grid->transform().worldToIndex(p)); }

private:
    using Sampler = LeafSampler;
    double exitDistance(const Vec3d& x, const Vec3d& dir) const;
    double entryDistance(const Vec3d& x, const Vec3d& dir) const;
    double voxelLengthsPerIndexUnit(const Vec3d& dir) const;

    const Volume& occluder_;
    const VisibleBlocks* reaching_;  // the occluder's; null: sample everywhere
    std::vector<RayInterval> intervals_;
    const DirectionalOrPointLight& light_;
    LightCacheSettings s_;
    openvdb::FloatGrid::ConstAccessor acc_;
    Sampler sampler_;
    openvdb::CoordBBox box_;
    Vec3d dirIndex_, lightIndex_;
    double stopDepth_, voxelLength_;
    bool uniform_;
};

}  // namespace weft
