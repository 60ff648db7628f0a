#pragma once
// The scene's participating media as integrators see them: along a world
// ray, the intervals where volumes lie (each volume's index box under its
// own affine transform) with a majorant each, and the extinction and
// scattering coefficients (RGB, per unit world length) at a point, summed
// over the volumes that overlap there:
//   sigma = density (trilinear, NaN/Inf and negatives read as 0)
//           x medium coefficient / voxelLength()
// (Volume::medium is per voxel length per unit density), the scattering
// tinted by the volume's colour grid (Volume::color: scattering x colour,
// the extinction unchanged, core/volume/volume_grids.hpp).
//
// Moving volumes (velocity motion blur, core/volume/volume_motion.hpp): a
// MediumRay carries a shutter time, and its lookups of a moving volume read
// every grid at the point advected back along the motion; each brick's
// majorant then covers every brick within the volume's reach, so the bound
// holds at any time in the shutter.
//
// Volumes are found through a flat list of their world bounds: scenes hold
// a handful of volumes, and each test is one box clip in index space.
// Majorants are per brick of 8^3 voxels (OpenVDB's leaf size): the largest
// finite density over the brick and its neighbours (trilinear lookups reach
// one voxel across), times the largest channel coefficient, walked along
// the ray by a 3D DDA. Thin and empty regions get small or zero majorants,
// so they cost few or no collisions; the bound holds everywhere, so
// tracking stays unbiased. Where a volume emits, a brick's majorant is at
// least one collision per voxel length, so emission is met even where the
// density is zero (see sampleFreeFlight).
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include <openvdb/openvdb.h>

#include "core/volume/grid/leaf_sampler.hpp"
#include "core/volume/media/volume_bvh.hpp"
#include "core/base/rng.hpp"
#include "core/volume/volume.hpp"
#include "core/volume/volume_motion.hpp"

namespace weft {

// Coefficients per unit world length at a point.
struct MediumCoefficients {
    Vec3d extinction{0.0};
    Vec3d scattering{0.0};
    Vec3d emission{0.0};  // emitted radiance per unit world length
    double g = 0;  // Henyey-Greenstein anisotropy (see FreeFlight where volumes overlap)
};

// One volume's stretch of a ray, in world distance along the (unit) ray.
struct MediumSegment {
    std::uint32_t volume = 0;
    double t0 = 0, t1 = 0;
    double majorant = 0;  // >= every channel of the extinction in the current brick
    Vec3d indexOrigin;    // index-space point at t = 0
    Vec3d indexStep;      // index-space motion per unit world distance
    // The DDA through the bricks: the current brick, where the ray crosses
    // into the next one per axis, and the majorant on [.., exit).
    openvdb::Coord brick;
    Vec3d crossing, crossingStep;
    double exit = 0;
};

// The majorant that holds on a stretch [t, next) of a ray: the sum over the
// segments covering it.
struct MajorantSpan {
    double majorant = 0;
    double next = 0;  // where the covering set changes (or the ray's end)
};

class Medium;

// Per-thread lookups (OpenVDB accessors cache tree paths and are not shared)
// along one ray at a time.
class MediumRay {
public:
    explicit MediumRay(const Medium& medium);

    // Clips the world ray (origin, unit dir) to every volume within [0, tMax).
    void reset(const Vec3d& origin, const Vec3d& dir, double tMax);
    // The shutter time (frames from the frame) of the rays that follow:
    // moving volumes are looked up where they are then.
    void setTime(double frames) { time_ = frames; }
    bool empty() const { return segments_.empty(); }
    double end() const { return end_; }
    const std::vector<MediumSegment>& segments() const { return segments_; }

    // t must not decrease between calls after a reset (the DDA walks forward).
    MajorantSpan majorantAt(double t);
    MediumCoefficients at(double t);
    // Where several volumes scatter at the last at() point, picks one's
    // phase function with probability by mean scattering and weights each
    // channel by (its share of that channel) / probability: an unbiased
    // one-sample estimate of the mixture of their phase functions.
    double pickPhase(Rng& rng, Vec3d& throughput) const;
    std::int64_t lookups = 0;

private:
    const Medium& medium_;
    void startBricks(MediumSegment& s);
    void nextBrick(MediumSegment& s);

    double brickMajorant(const MediumSegment& s);

    std::vector<openvdb::FloatGrid::ConstAccessor> accessors_, brickAccessors_;
    std::vector<LeafSampler> samplers_;  // through accessors_ (a move keeps their addresses)
    std::vector<std::optional<openvdb::Vec3SGrid::ConstAccessor>> emissionAccessors_;
    std::vector<std::optional<Vec3LeafSampler>> emissionSamplers_;  // through emissionAccessors_
    std::vector<std::optional<openvdb::Vec3SGrid::ConstAccessor>> colorAccessors_;
    std::vector<std::optional<Vec3LeafSampler>> colorSamplers_;  // through colorAccessors_
    std::deque<std::optional<MotionLookup>> motions_;          // built in place
    double time_ = 0;
    void addSegment(std::uint32_t volume, const Vec3d& origin, const Vec3d& dir, double tMax);

    std::vector<MediumSegment> segments_;
    std::vector<std::uint32_t> crossed_;  // the BVH's answer
    struct Lobe {
        double g;
        Vec3d scattering;
    };
    std::vector<Lobe> lobes_;  // of the last at() point
    double end_ = 0;
};

class Medium {
public:
    // Keeps pointers to the volumes: they must outlive it (no temporaries).
    explicit Medium(const std::vector<Volume>& volumes);
    explicit Medium(std::vector<Volume>&&) = delete;
    bool empty() const { return volumes_.empty(); }

private:
    friend class MediumRay;
    struct Entry {
        const Volume* volume;
        Vec3d absorb, scatter;  // per world length per unit density
        double coefficientMax;  // largest channel of absorb + scatter
        openvdb::FloatGrid::Ptr bricks;  // per brick: density bound (see above)
        openvdb::FloatGrid::Ptr emissiveBricks;  // per brick: 1 where it (or a neighbour) emits; null: no emission
        double emissionRate = 0;                 // the majorant's floor there, per world length
    };
    std::vector<Entry> volumes_;  // non-empty volumes only
    VolumeBvh bvh_;               // of their world boxes, with two or more
};

// Henyey-Greenstein phase function of the cosine between the travel
// direction and the scattered direction; integrates to 1 over the sphere.
double henyeyGreenstein(double g, double cosTheta);
// The cosine of a direction drawn from it with uniform u in [0, 1).
double sampleHenyeyGreensteinCos(double g, double u);
// A direction around the travel direction d (unit) drawn from it.
Vec3d sampleHenyeyGreenstein(const Vec3d& d, double g, double u1, double u2);

// Transmittance estimators along a MediumRay over [0, ray.end()).
// Ratio tracking: every tentative collision weights by 1 - sigma/majorant.
// Delta tracking: a tentative collision is real with probability
// min-channel sigma / majorant (a real one ends the ray at 0); a null one
// weights each channel by (1 - sigma_c/majorant) / (1 - P), so every
// channel is unbiased and equal channels give the binary estimator.
Vec3d ratioTrackingTransmittance(MediumRay& ray, Rng& rng, std::int64_t& collisions);
Vec3d deltaTrackingTransmittance(MediumRay& ray, Rng& rng, std::int64_t& collisions);

// Free flight by weighted delta tracking against the majorant: at a
// tentative collision, scattering is chosen with probability proportional
// to the throughput-weighted mean of sigma_s, a null collision to that of
// (majorant - sigma_t); absorption is folded into the weights, so each
// channel's estimate is unbiased (Kutz et al. 2017, spectral tracking).
// Where volumes overlap, the phase function is picked by pickPhase.
// Emission is gathered on the way: every tentative collision adds
// throughput x emission / majorant, an unbiased estimate of the
// transmittance-weighted emission up to the scattering point (or the end).
struct FreeFlight {
    bool scattered = false;  // else the ray reached ray.end() (or died: weight 0)
    double t = 0;
    MediumCoefficients coefficients;  // at the scattering point
    Vec3d emitted{0.0};               // throughput-weighted emission met before it
};
FreeFlight sampleFreeFlight(MediumRay& ray, Rng& rng, Vec3d& throughput, std::int64_t& collisions);

}  // namespace weft
