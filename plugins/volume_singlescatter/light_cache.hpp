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
#include <openvdb/openvdb.h>

#include "core/volume/volume.hpp"
#include "plugins/volume_singlescatter/scatter_params.hpp"

namespace weft {

struct LightCacheSettings {
    double step;        // march step, voxels
    double gain;        // vdb_render's gain
    double cutoff;      // densities below it count as empty
    double sigmaMin;    // smallest extinction coefficient (stops the march once T < 1e-4 in every channel)
    int coarsening;     // cache voxels are this many density voxels wide
};

// D for a directional light (toLight in world space) or a point light.
openvdb::FloatGrid::Ptr buildLightCache(const Volume& volume, const DirectionalOrPointLight& light,
                                        const LightCacheSettings& settings);

}  // namespace weft
