#pragma once
// The light transport of volume.singlescatter for one render: a camera ray
// marches every volume it crosses (overlapping ones add their extinction)
// and ends at the first surface, which is lit by the same lights through
// the meshes and the volumes' transmittance and composited behind:
//   L = L_volume + T * L_surface.
//
// Step rule: a camera ray steps `step` voxel lengths (cube root of a
// voxel's volume) of the finest volume it crosses, and a shadow ray
// `shadowstep` voxel lengths of the volume it crosses. On uniform grids a
// voxel length is one index unit, so one uniform volume marches exactly as
// before. A sample where several volumes have density scatters in
// proportion to each one's scattering coefficient (with its own phase).
//
// A volume's colour grid tints its albedo at each sample (scattering x
// colour, the extinction unchanged: core/volume/volume_grids.hpp).
//
// Moving volumes (velocity motion blur): every lookup of a camera sample,
// along its primary ray and its shadow rays, reads the volume where it is
// at the sample's shutter time (core/volume/volume_motion.hpp; the
// intersectors' occupancy is dilated by the reach). The light cache holds
// the volumes as they stand: a moving receiver reads it where the sample
// came from, which is exact for a volume translating as a whole under
// directional lights and first order otherwise; surfaces then trace their
// shadow rays, and estimator=ratio or raymarch traces every shadow ray
// through the moving volumes.
#include <openvdb/tools/Interpolation.h>

#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "core/base/run/render_context.hpp"
#include "core/base/rng.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/volume/skip/screen_footprint.hpp"
#include "core/volume/media/volume_bvh.hpp"
#include "plugins/volume_singlescatter/light_cache.hpp"
#include "plugins/volume_singlescatter/scatter_volume.hpp"

namespace weft {

class ScatterTracer {
public:
    // accel: the scene's BVH, or null when it has no meshes.
    ScatterTracer(const Scene& scene, const ScatterParams& params, std::vector<ScatterVolume> volumes,
                  const MeshAccel* accel, float eps);
    void buildCaches(RenderContext& ctx);  // estimator=cached

    class Row;  // per-thread state: accessors, intersector copies, counts
    struct RowDeleter {
        void operator()(Row* row) const;
    };
    std::unique_ptr<Row, RowDeleter> row() const;

    struct Counts {
        std::int64_t samples = 0, shadowSamples = 0, meshShadowRays = 0;
    };
    static const Counts& counts(const Row& row);

    // Radiance of a camera ray; T returns the volumes' transmittance in
    // front of it and surface whether it ended at a surface.
    // time: the camera sample's shutter time, frames from the frame (moving volumes).
    // seen false: the ray is outside footprint()'s pixels and skips the volumes.
    Vec3d radiance(const Ray& ray, float offset, double time, Row& row, Rng& rng, Vec3d& T, bool& surface, bool seen = true) const;
    // The pixels whose camera rays can take a sample: every volume's reaching
    // boxes projected (core/volume/skip/screen_footprint.hpp). None where a
    // volume marches its intersector's spans instead (emission, motion).
    std::optional<ScreenFootprint> footprint(const CameraRays& rays, int width, int height) const;

private:
    struct Share {  // one volume's part of a sample
        std::size_t volume;
        double weight;  // density x its voxel lengths per march unit
        Vec3d tint;     // its colour grid there (1: untinted)
    };
    struct EmitterLight {  // one emitter sample: direction, radiance x transmittance / pdf
        Vec3d toLight{0.0}, radiance{0.0};
        bool valid = false;
    };
    const std::vector<std::uint32_t>& crossed(const Vec3d& origin, const Vec3d& dir, double tMax, Row& row) const;
    EmitterLight emitterLight(const Vec3d& p, Row& row, Rng& rng) const;
    Vec3d scattering(const std::vector<Share>& shares, const Vec3d& sigmaT, double cosTheta) const;
    bool marchVolumes(const Ray& ray, double tSurface, float offset, Row& row, Rng& rng, Vec3d& T, Vec3d& L) const;
    bool marchOne(const Ray& ray, double uSurface, float offset, Row& row, Rng& rng, Vec3d& T, Vec3d& L) const;
    Vec3d inscatter(const Vec3d& p, const Vec3d& viewDir, const std::vector<Share>& shares, const Vec3d& sigmaT,
                    Row& row, Rng& rng) const;
    Vec3d shadow(std::size_t light, const Vec3d& p, const Vec3d& toLight, double distance, std::size_t receiver, Row& row,
                 Rng& rng) const;
    Vec3d tracedShadow(const Vec3d& p, const Vec3d& toLight, double distance, Row& row, Rng& rng) const;
    Vec3d shadowThrough(std::size_t volume, const Vec3d& p, const Vec3d& toLight, double distance, Row& row, Rng& rng,
                        Vec3d T) const;
    Vec3d surfaceRadiance(const Ray& ray, const SurfaceHit& hit, Row& row, Rng& rng) const;
    Vec3d surfaceShadow(std::size_t light, const Vec3d& p, const Vec3d& toLight, double distance, Row& row, Rng& rng) const;
    double phase(const ScatterVolume& v, double cosTheta) const;
    std::size_t cacheIndex(std::size_t light, std::size_t receiver, std::size_t occluder) const {
        return (light * volumes_.size() + receiver) * volumes_.size() + occluder;
    }

    const Scene& scene_;
    const ScatterParams& params_;
    std::vector<ScatterVolume> volumes_;
    const MeshAccel* accel_;
    float eps_;
    bool moving_;  // some volume moves while the shutter is open
    // [volume], with the cache: where the cache's march samples (every leaf's
    // values count, not only the active leaves' that camera rays read).
    std::vector<std::shared_ptr<const VisibleBlocks>> cacheReaching_;
    std::vector<openvdb::FloatGrid::ConstPtr> densityCaches_;  // [light][receiver][occluder]
    std::vector<openvdb::FloatGrid::Ptr> visibilityCaches_;
    VolumeBvh bvh_;  // with two or more volumes  // [light][receiver], with meshes only
};

}  // namespace weft
