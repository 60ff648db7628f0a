#pragma once
// Emission-absorption marching of one camera ray through every volume it
// crosses, front to back, ending at an optional surface.
//
// Step rule for several volumes: the march runs in units of the smallest
// voxel length among the volumes this ray crosses (u = world distance /
// that length) and takes one sample every `step` such units, from the
// first volume's entry. At each sample every volume whose index box holds
// the point is looked up; extinctions add (each scaled from its own voxel
// length to the common unit) and emissions add, so the segment's colour is
// the extinction-weighted mean of the volumes' colours. With one volume this
// is exactly the single-volume march: u is its index t (on uniform voxels).
// On anisotropic or sheared grids a voxel length is the cube root of the
// voxel's volume, so optical depth follows world distance, not index steps.
//
// A volume's emission grid (radiance per voxel length) adds to the
// transfer function's colour: a segment of opacity a at extinction s per
// unit length and emission e contributes c a + e (1 - exp(-s L)) / s, the
// exact integral of constant emission over it (e L where s -> 0).
//
// A moving volume (Volume::motion, an open shutter) is looked up at
// p - motion(p) t for the ray's shutter time t (frames from the frame):
// first-order backward advection of all its grids (core/volume/
// volume_motion.hpp); such rays take the general per-sample path.
//
// A surface at world ray parameter tSurface ends the march exactly: the
// segments before it are whole, the last one is cut at the surface and
// integrated with its true length.
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/RayIntersector.h>

#include <deque>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "core/volume/grid/leaf_sampler.hpp"
#include "core/volume/skip/screen_footprint.hpp"
#include "core/volume/skip/visible_blocks.hpp"
#include "core/volume/skip/visible_cells.hpp"
#include "core/volume/media/volume_bvh.hpp"
#include "core/volume/volume_motion.hpp"
#include "core/scene/scene.hpp"
#include "core/volume/volume_ray.hpp"

namespace weft {

using VolumeSampler = LeafSampler;
using VolumeIntersector = openvdb::tools::VolumeRayIntersector<openvdb::FloatGrid, 0>;

struct MarchSettings {
    double step = 0.5;  // in voxel lengths of the finest volume crossed
    float ertOpacity = 0.99f;
    const VolumeBvh* bounds = nullptr;  // of the scene's volumes (null: test each one)
    std::vector<const DenseCopy<openvdb::FloatGrid>*> dense;  // per volume, where it has one (may be short)
};

// skip_empty's HDDA masters, one per volume, built once per render on the
// cells of each grid that its transfer function can show (visibleCells, in
// index space: OpenVDB's intersector needs uniform voxels); an emitting
// volume's also hold its emission's active voxels. The HDDA skips whole
// 8^3 leaves; inside the leaves it marches, a still volume without emission
// is looked up only in its visible cells (VisibleCellTest: on the aneurism at
// step 1, 4.3 M lookups become 0.3 M). Every sample skipped has zero
// extinction and no emission, so the image is the full march's.
class EmptySpaceSkipper {
public:
    explicit EmptySpaceSkipper(const std::vector<Volume>& volumes);
    // Null where the volume's transfer function hides all of it, or its blocks replace it.
    const VolumeIntersector* of(std::size_t volume) const { return intersectors_[volume].get(); }
    // The volume's visible cells where they alone decide what to march (no
    // emission, no motion); null otherwise.
    const openvdb::FloatGrid* cells(std::size_t volume) const { return cells_[volume].get(); }
    // The blocks of those cells where their array is small enough (it then
    // replaces the HDDA); null otherwise.
    const VisibleBlocks* blocks(std::size_t volume) const { return blocks_[volume].get(); }
    // Whether skipping pays: the leaves and active tiles left to march fill
    // at most 3/4 of the volumes' active boxes (raymarch, one thread,
    // measured on whole grids: the aneurism, 0.31 full, 1.9x faster; the
    // Gaffer smoke, 0.58 full, 1.37x; data/smoke_small.vdb, 0.96 full, 0.85x).
    bool pays() const { return pays_; }
    // The image's pixels whose camera rays may add something: every
    // visible box of every volume projected (core/volume/skip/screen_footprint.hpp).
    // None where a volume the transfer function shows has no blocks (the
    // HDDA then decides ray by ray).
    std::optional<ScreenFootprint> footprint(const std::vector<Volume>& volumes, const CameraRays& rays, int width, int height) const;

private:
    std::vector<openvdb::FloatGrid::ConstPtr> indexGrids_;  // the intersectors point into these
    std::vector<std::unique_ptr<VolumeIntersector>> intersectors_;
    std::vector<openvdb::FloatGrid::ConstPtr> cells_;
    std::vector<std::unique_ptr<VisibleBlocks>> blocks_;
    bool pays_ = false;
};

// The skipper of these volumes, shared between renders of one process: a
// frame sequence of a static volume and the runs of a sweep build it once
// (core/volume/volume_key.hpp says when two volumes are the same; moving
// volumes, whose skipper depends on their reach, are not shared). The last
// kSkipperCacheEntries are kept. Thread-safe.
struct SharedSkipper {
    std::shared_ptr<const EmptySpaceSkipper> skipper;
    bool reused = false;  // found in the cache, not built by this call
};
SharedSkipper sharedEmptySpaceSkipper(const std::vector<Volume>& volumes);
constexpr int kSkipperCacheEntries = 2;
void clearSkipperCache();  // tests

// Whether skip_empty may skip at all: some volume is not empty, every
// background is transparent, and no volume moves more than 16 voxels within
// the shutter (the skipper dilates a moving volume's occupancy by its reach,
// one pass per voxel).
bool emptySpaceSkippable(const std::vector<Volume>& volumes);
// skip_empty=auto: skippable, and the skipper pays.
bool emptySpacePays(const std::vector<Volume>& volumes);

// Per thread (one per image row): grid accessors, HDDA copies, counts.
class VolumeMarcher {
public:
    VolumeMarcher(const Scene& scene, const MarchSettings& settings, const EmptySpaceSkipper* skipper);
    VolumeMarcher(const VolumeMarcher&) = delete;
    VolumeMarcher& operator=(const VolumeMarcher&) = delete;

    // offset in [0, 1): where the sample sits inside each step; time: the
    // ray's shutter time in frames from the frame (moving volumes only);
    // [t0, t1]: the stretch of the ray (its world parameter) that holds
    // every visible block it crosses (a ScreenFootprint's rayRange), where
    // the walk through the blocks starts and ends. The image is the same.
    RayAccumulator march(const Ray& ray, double tSurface, float offset, double time = 0,
                         double t0 = -std::numeric_limits<double>::infinity(),
                         double t1 = std::numeric_limits<double>::infinity());
    std::int64_t samples() const { return samples_; }

private:
    struct Lookup {  // one volume, built in place: the sampler points at the accessor
        const Volume& volume;
        openvdb::FloatGrid::ConstAccessor accessor;
        VolumeSampler sampler;
        std::optional<openvdb::Vec3SGrid::ConstAccessor> emissionAccessor;
        std::optional<Vec3LeafSampler> emission;  // through emissionAccessor
        std::optional<MotionLookup> motion;
        std::optional<VolumeIntersector> hdda;
        // skip_empty's cells where they decide alone: their blocks where those
        // replace the HDDA (which then answer the cell test too), else the grid.
        std::optional<VisibleCellTest> visible;
        const VisibleBlocks* blocks = nullptr;
        double voxelLength;
        bool uniform;  // uniform voxels: index units are voxel lengths exactly
        Lookup(const Volume& v, const EmptySpaceSkipper* skipper, std::size_t index);
        // False where a sample at index point p adds nothing: a hidden cell.
        bool shows(const Vec3d& p) { return blocks ? blocks->cellVisible(p) : !visible || (*visible)(p); }
    };
    struct Crossing {  // one volume on the current ray
        Lookup* lookup;
        IndexRay ray;
        double perU;        // its index units per march unit
        float depthScale;   // its voxel lengths per march unit
    };

    bool cross(const Ray& ray);
    void collectIntervals(double uEnd);
    bool marchInterval(const RayInterval& in, double kMax, float offset, RayAccumulator& acc);
    bool marchEmitting(const RayInterval& in, double kMax, float offset, RayAccumulator& acc);
    template <class AddSegment>
    bool marchSteps(const RayInterval& in, double kMax, float offset, RayAccumulator& acc, AddSegment&& add);
    void addSegment(double u, double length, RayAccumulator& acc);

    MarchSettings settings_;
    std::deque<Lookup> lookups_;
    std::vector<Crossing> crossings_;
    std::vector<std::uint32_t> crossed_;  // the bounds' answer
    std::vector<RayInterval> intervals_;  // march units
    double time_ = 0;      // the current ray's shutter time, frames
    bool moving_ = false;  // a crossed volume moves at time_
    bool skipping_ = false;  // marching only the skipper's intervals
    double u0_ = 0, uEnd_ = 0, unitLength_ = 1;  // first entry, last exit, world length of a march unit
    double blocksFrom_ = 0, blocksTo_ = 0;        // the world stretch march() was given for the walk through the blocks
    std::int64_t samples_ = 0;
};

}  // namespace weft
