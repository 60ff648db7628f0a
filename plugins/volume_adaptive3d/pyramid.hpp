#pragma once
// The image pyramid of volume.adaptive3d: per level, the rays and the
// stored data values s (one per volume), emission e (one per volume, only
// when a volume emits) and oracle distance d (in slices) of every pixel;
// on level 0 also the previous composite's slice, value and emission and
// the accumulated colour. SliceWorker is the body of Figure 4 for one row.
#include <algorithm>
#include <bit>
#include <climits>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "core/base/run/counters.hpp"
#include "core/image/image.hpp"
#include "core/volume/optics/segment_tables.hpp"
#include "core/volume/slice/slice_volumes.hpp"
#include "core/volume/slice/slices.hpp"
#include "oracles/oracle.hpp"
#include "core/volume/slice/slice_renderer.hpp"

namespace weft {

// l_slice: trailing zeros of the slice index, at most lmax (Table 1).
inline int sliceLevel(int slice, int lmax) {
    return slice == 0 ? lmax : std::min(std::countr_zero(unsigned(slice)), lmax);
}

// Whether a pixel whose stored distance is d (slices) is composited on a
// slice of level lslice: the skipping rule d >= 2^(lslice+1) negated.
inline bool isDue(float d, int lslice, int lmax) { return lslice == lmax || d < float(2 << lslice); }

// A pixel is due on slices of level >= floor(log2 d); 8x8 tiles keep the
// smallest such level of their pixels so that a slice can pass over tiles
// with nothing due without visiting their pixels (early rejection).
constexpr int kTile = 8;
inline std::uint8_t dueLevel(float d) { return std::uint8_t(std::bit_width(unsigned(d)) - 1); }

struct PyramidLevel {
    LevelRays rays;
    FreshBuffer<float> s;  // normalised data value, [volume * pixels + pixel]
    std::vector<Vec3f> e;  // emission, laid out as s; empty when no volume emits
    FreshBuffer<float> d;  // sampling distance, slices
    int tilesX = 0, tilesY = 0;
    std::vector<std::uint8_t> tileDueLevel;  // min dueLevel(d) over the tile
    // 1 where every pixel of the tile holds the background (no emission) at
    // the longest distance: the tile is then due on full slices only, and
    // there, if its parents are quiet too, it stays as it is.
    std::vector<std::uint8_t> tileQuiet;
    // Angle between neighbouring level-0 rays: at distance t from the eye
    // they are t * pixelAngle voxels apart.
    double pixelAngle = 0;
};

// Where the pixels' rays meet their first surfaces, in slices. Level 0
// holds each pixel's last slice in front of its surface (kNoSurface: none
// inside the slices, -1: the surface is before the first slice); level l
// the smallest (lo) and largest (hi) of its 2^l x 2^l level-0 pixels, so a
// coarse sample knows both the nearest surface in its footprint and whether
// the footprint holds a depth discontinuity (lo < hi). Empty without meshes.
struct SurfaceSlices {
    static constexpr int kNoSurface = INT_MAX;
    std::vector<std::vector<int>> lo, hi;  // [level][pixel]
    std::vector<double> tHit;              // level 0: distance to the surface, voxels
    bool any() const { return !lo.empty(); }
};

// volume.adaptive3d's parameter table (its replays in hwsim share it).
std::vector<ParamSpec> adaptiveParamSpecs();

class Pyramid {
public:
    Pyramid(const Camera& camera, const std::vector<SliceVolume>& volumes, const SliceSetup& slices, int lmax, int paddedWidth,
            int paddedHeight, int imageWidth, int imageHeight);
    PyramidLevel& level(int l) { return levels_[l]; }
    const PyramidLevel& level(int l) const { return levels_[l]; }
    // Level-0 compositing state.
    FreshBuffer<float> sPrev;  // [volume * pixels + pixel]
    std::vector<Vec3f> ePrev;  // the same for emission; empty when no volume emits
    FreshBuffer<int> iPrev;
    // Per level-0 tile: the last slice on which the tile was passed over as
    // quiet (-1: none since its pixels were last visited). Its pixels were
    // composited there, so their iPrev is that slice.
    std::vector<int> quietComposite;
    FreshBuffer<SegmentCompositor> color;
    SurfaceSlices surfaces;
    // Fills `surfaces` from level 0's distances (infinity: no surface).
    void setSurfaces(std::vector<double> tHit, const SliceSetup& slices);
    // The accumulated colour, cropped to the image.
    Image image(int width, int height) const;

private:
    std::vector<PyramidLevel> levels_;
};

// fields[k]: volume k's oracle, in its own voxels.
struct SliceContext {
    const std::vector<SliceVolume>& volumes;
    const std::vector<OracleField>& fields;
    const SliceSetup& slices;
    SliceTables& tables;
    int lmax;
    Counters& counters;
    double time = 0;  // the pass's shutter time, frames from the frame (moving volumes only)
};

class SliceWorker {
public:
    explicit SliceWorker(SliceContext& sc);
    // Figure 4's body for the pixels of one tile; returns the tile's new due level.
    std::uint8_t tile(Pyramid& pyramid, int l, int lslice, int slice, int tx, int ty);
    void flush();  // adds this worker's counts to the counters

    // The three operations of Figure 4 on one pixel (hwsim's replays run
    // them as fragment programs of the paper's GPU passes).
    void synthesize(Pyramid& pyramid, int l, int x, int y, int idx, int slice);
    void sample(Pyramid& pyramid, int l, int idx, int slice);
    void composite(Pyramid& pyramid, int idx, int slice);

private:
    // Level l's distance d bounded by the surfaces of its footprint after slice `slice`.
    float surfaceBound(const Pyramid& pyramid, int l, int idx, int slice, float d) const;
    // The operations compiled per case: one volume or several, with surfaces or without.
    template <bool kOne, bool kSurfaces> struct Case {
        static constexpr bool one = kOne, surfaces = kSurfaces;
    };
    template <typename F> decltype(auto) dispatch(const Pyramid& pyramid, F&& f);
    template <bool kOne, bool kSurfaces> std::uint8_t tileOf(Pyramid& pyramid, int l, int lslice, int slice, int tx, int ty);
    // Whether a tile of level l stays as it is on a full slice: it is quiet
    // and so are the coarse tiles its pixels are synthesized from.
    bool staysQuiet(const Pyramid& pyramid, int l, int tx, int ty) const;
    // Background at the longest distance; on level 0 also composited last with the background.
    bool pixelQuiet(const Pyramid& pyramid, int l, int idx) const;
    template <bool kOne, bool kSurfaces> void synthesizeOf(Pyramid& pyramid, int l, int x, int y, int idx, int slice);
    template <bool kOne, bool kSurfaces> void sampleOf(Pyramid& pyramid, int l, int idx, int slice);
    template <bool kOne, bool kSurfaces> void compositeOf(Pyramid& pyramid, int idx, int slice);
    void compositeToSurface(Pyramid& pyramid, int idx, int slice);
    // sample()'s and composite()'s work for one volume (the common case, kept
    // as cheap as before volumes could overlap) and for several.
    // A sample's distance in slices: dVoxels in slice or pixel widths, clamped, bounded by surfaces.
    template <bool kSurfaces> float slicesToSkip(const Pyramid& pyramid, int l, int idx, int slice, float dVoxels) const;
    float sampleOneVolume(PyramidLevel& level, int l, int idx, int slice, const Vec3d& p);
    float sampleVolumes(PyramidLevel& level, int l, int idx, int slice, const Vec3d& p);
    void compositeOneVolume(Pyramid& pyramid, int idx, int slice);
    void compositeVolumes(Pyramid& pyramid, int idx, int slice);

    SliceContext& sc_;
    // Volume k's oracle distance at reference position p, in reference voxels.
    float oracleDistance(int k, const Vec3d& p);

    SliceSamplers data_;
    std::deque<RingAccessor> oracleAccessors_;
    std::vector<PreintSample> segments_;  // one per volume
    // One volume in its own index space (no placement between the reference
    // and it) that emits nothing and stays still; emitting and moving scenes
    // take the general path.
    bool one_ = false;
    bool emits_ = false;  // some volume emits
    // Synthesizing from four background parents gives the background to the
    // bit (always for a background of 0), so quiet tiles may be passed over.
    bool quietSkips_ = false;
    const ScalarSampler* sampler0_ = nullptr;
    RingAccessor* oracle0_ = nullptr;
    float background0_ = 0;
    SegmentTables* tables0_ = nullptr;
    std::int64_t samples_ = 0, oracleSamples_ = 0, syntheses_ = 0, composites_ = 0;
    std::int64_t samplesPerLevel_[8] = {};  // where the samples go: volume.samples.level<l>
};

// One SliceWorker per thread for a whole pass: its samplers, accessors
// (each registered with its tree) and buffers are made once per thread, not
// once per parallel chunk of every level of every slice. A worker's
// operations must not wait on parallel work: the waiting thread could pick
// up another chunk and enter its own worker again.
class SliceWorkers {
public:
    explicit SliceWorkers(SliceContext& sc) : sc_(sc) {}
    SliceWorker& local() {
        std::unique_ptr<SliceWorker>& w = workers_.local();
        if (!w) w = std::make_unique<SliceWorker>(sc_);
        return *w;
    }
    // Adds every worker's counts to the counters; once, at the pass's end.
    void flush() {
        for (auto& w : workers_)
            if (w) w->flush();
    }

private:
    SliceContext& sc_;
    tbb::enumerable_thread_specific<std::unique_ptr<SliceWorker>> workers_;
};

}  // namespace weft
