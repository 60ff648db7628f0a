#pragma once
// The image pyramid of volume.adaptive3d: per level, the rays and the
// stored data value s and oracle distance d (in slices) of every pixel;
// on level 0 also the previous composite's slice and value and the
// accumulated colour. SliceWorker is the body of Figure 4 for one row.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "core/base/counters.hpp"
#include "core/image/image.hpp"
#include "core/volume/segment_tables.hpp"
#include "core/volume/slices.hpp"
#include "oracles/oracle.hpp"
#include "core/volume/slice_renderer.hpp"

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
    std::vector<float> s;  // normalised data value
    std::vector<float> d;  // sampling distance, slices
    int tilesX = 0, tilesY = 0;
    std::vector<std::uint8_t> tileDueLevel;  // min dueLevel(d) over the tile
    // Angle between neighbouring level-0 rays: at distance t from the eye
    // they are t * pixelAngle voxels apart.
    double pixelAngle = 0;
};

// volume.adaptive3d's parameter table (its replays in hwsim share it).
std::vector<ParamSpec> adaptiveParamSpecs();

class Pyramid {
public:
    Pyramid(const Camera& camera, const Volume& volume, const SliceSetup& slices, int lmax, int paddedWidth,
            int paddedHeight, int imageWidth, int imageHeight);
    PyramidLevel& level(int l) { return levels_[l]; }
    // Level-0 compositing state.
    std::vector<float> sPrev;
    std::vector<int> iPrev;
    std::vector<SegmentCompositor> color;
    // The accumulated colour, cropped to the image.
    Image image(int width, int height) const;

private:
    std::vector<PyramidLevel> levels_;
};

struct SliceContext {
    const Volume& volume;
    const OracleField& field;
    const SliceSetup& slices;
    SegmentTables& tables;
    int lmax;
    Counters& counters;
};

class SliceWorker {
public:
    explicit SliceWorker(SliceContext& sc);
    // Figure 4's body for the pixels of one tile; returns the tile's new due level.
    std::uint8_t tile(Pyramid& pyramid, int l, int lslice, int slice, int tx, int ty);
    void flush();  // adds this worker's counts to the counters

    // The three operations of Figure 4 on one pixel (hwsim's replays run
    // them as fragment programs of the paper's GPU passes).
    void synthesize(Pyramid& pyramid, int l, int x, int y, int idx);
    void sample(PyramidLevel& level, int l, int idx, int slice);
    void composite(Pyramid& pyramid, int idx, int slice);

private:
    SliceContext& sc_;
    ScalarSampler data_;
    openvdb::FloatGrid::ConstAccessor oracleAccessor_;
    std::int64_t samples_ = 0, oracleSamples_ = 0, syntheses_ = 0, composites_ = 0;
    std::int64_t samplesPerLevel_[8] = {};  // where the samples go: volume.samples.level<l>
};

}  // namespace weft
