#include "plugins/volume_adaptive3d/pyramid.hpp"

#include <algorithm>
#include <cmath>

namespace weft {

namespace {
const Counter kOracleSamples{"oracle.samples", "oracle lookups (the paper's SAMPLE ORACLE)"};
const Counter kSynthesisOps{"synthesis.ops", "per-pixel syntheses of data and oracle (the paper's SYNTHESIZE)"};
const IndexedCounter kVolumeSamplesLevel{"volume.samples.level", "volume lookups at pyramid level N"};
}  // namespace

Pyramid::Pyramid(const Camera& camera, const Volume& volume, const SliceSetup& slices, int lmax, int paddedWidth,
                 int paddedHeight, int imageWidth, int imageHeight) {
    const float background = float(volume.tf.normalize(volume.grid->background()));
    for (int l = 0; l <= lmax; ++l) {
        PyramidLevel level;
        level.rays = makeLevelRays(camera, volume, slices, l, paddedWidth, paddedHeight, imageWidth, imageHeight);
        level.s.assign(level.rays.dir.size(), background);
        level.d.assign(level.rays.dir.size(), 1.0f);
        level.tilesX = (level.rays.width + kTile - 1) / kTile;
        level.tilesY = (level.rays.height + kTile - 1) / kTile;
        level.tileDueLevel.assign(std::size_t(level.tilesX) * level.tilesY, 0);
        level.pixelAngle = 2.0 * std::tan(0.5 * camera.fovY * M_PI / 180.0) / imageHeight;
        levels_.push_back(std::move(level));
    }
    const std::size_t n = levels_[0].rays.dir.size();
    sPrev.assign(n, background);
    iPrev.assign(n, 0);
    color.assign(n, SegmentCompositor{});
}

Image Pyramid::image(int width, int height) const {
    Image img = Image::rgba(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const SegmentCompositor& c = color[levels_[0].rays.index(x, y)];
            float* px = img.pixel(x, y);
            px[0] = c.r, px[1] = c.g, px[2] = c.b, px[3] = c.a;
        }
    return img;
}

SliceWorker::SliceWorker(SliceContext& sc)
    : sc_(sc), data_(sc.volume),
      oracleAccessor_(sc.field.distance ? sc.field.distance->getConstAccessor() : sc.volume.grid->getConstAccessor()) {}

std::uint8_t SliceWorker::tile(Pyramid& pyramid, int l, int lslice, int slice, int tx, int ty) {
    PyramidLevel& level = pyramid.level(l);
    const float sampleBelow = float(2 << l);  // 2^(l+1)
    const int x1 = std::min(level.rays.width, (tx + 1) * kTile), y1 = std::min(level.rays.height, (ty + 1) * kTile);
    std::uint8_t minDue = 255;
    for (int y = ty * kTile; y < y1; ++y)
        for (int x = tx * kTile; x < x1; ++x) {
            const int idx = level.rays.index(x, y);
            if (l < lslice && isDue(level.d[idx], lslice, sc_.lmax)) synthesize(pyramid, l, x, y, idx);
            const float d = level.d[idx];
            const bool accumulate = l == 0 && isDue(d, lslice, sc_.lmax);
            if (l == sc_.lmax || d < sampleBelow) sample(level, l, idx, slice);
            if (accumulate) composite(pyramid, idx, slice);
            minDue = std::min(minDue, dueLevel(level.d[idx]));
        }
    return minDue;
}

// Figures 5-7: bilinear interpolation of the coarser level at this pixel's
// centre, i.e. weights 9/16, 3/16, 3/16, 1/16 of the four nearest parents.
void SliceWorker::synthesize(Pyramid& pyramid, int l, int x, int y, int idx) {
    PyramidLevel& fine = pyramid.level(l);
    const PyramidLevel& coarse = pyramid.level(l + 1);
    const int cw = coarse.rays.width, ch = coarse.rays.height;
    const int x0 = (x - 1) >> 1, y0 = (y - 1) >> 1;                   // parent at or left/above the centre
    const float fx = (x & 1) ? 0.25f : 0.75f, fy = (y & 1) ? 0.25f : 0.75f;  // weight of the second parent
    const int xa = std::clamp(x0, 0, cw - 1), xb = std::clamp(x0 + 1, 0, cw - 1);
    const int ya = std::clamp(y0, 0, ch - 1), yb = std::clamp(y0 + 1, 0, ch - 1);
    auto blend = [&](const std::vector<float>& v) {
        const float top = (1 - fx) * v[ya * cw + xa] + fx * v[ya * cw + xb];
        const float bottom = (1 - fx) * v[yb * cw + xa] + fx * v[yb * cw + xb];
        return (1 - fy) * top + fy * bottom;
    };
    fine.s[idx] = blend(coarse.s);
    fine.d[idx] = blend(coarse.d);
    ++syntheses_;
}

// The oracle is asked on every sample, inside the volume's box or not: a
// coarse ray may still be outside while the finer rays that inherit its
// distance are already inside.
void SliceWorker::sample(PyramidLevel& level, int l, int idx, int slice) {
    const LevelRays& rays = level.rays;
    const openvdb::Vec3d p = sc_.slices.eye + rays.dir[idx] * sc_.slices.t(slice);
    const bool inside = slice >= rays.first[idx] && slice <= rays.last[idx];
    float dVoxels = sc_.field.at(oracleAccessor_, p);
    oracleSamples_ += inside || sc_.field.distance;  // a constant oracle costs nothing outside
    if (inside) {
        level.s[idx] = data_.sample(p);
        ++samples_, ++samplesPerLevel_[l];
    } else {
        level.s[idx] = data_.background();
        // Before the volume, skip no further than the slice just in front of
        // it, whose background sample starts the first segment inside.
        if (slice < rays.first[idx])
            dVoxels = std::min(dVoxels, float(std::max(1, rays.first[idx] - 1 - slice) * sc_.slices.spacing));
    }
    // The skipping rule counts image-plane and ray distances in one unit
    // (Kraus et al. assume pixels no wider than a slice): where pixels are
    // wider, distances are counted in pixel widths, so a coarse level never
    // skips a feature between its rays.
    const double unit = std::max(sc_.slices.spacing, sc_.slices.t(slice) * level.pixelAngle);
    const float maxSlices = float(1 << sc_.lmax);
    level.d[idx] = std::clamp(float(dVoxels / unit), 1.0f, maxSlices);
}

// Figure 8: the segment from the previous composite to this slice. A
// segment with background at both ends adds nothing (the transfer function
// is transparent there), so it costs no table lookup.
void SliceWorker::composite(Pyramid& pyramid, int idx, int slice) {
    const float s0 = pyramid.level(0).s[idx];
    const float empty = data_.background();
    if (slice > 0 && !(s0 == empty && pyramid.sPrev[idx] == empty)) {
        const int length = slice - pyramid.iPrev[idx];
        pyramid.color[idx].add(sc_.tables.forSlices(length).lookup(0, pyramid.sPrev[idx], s0));
        ++composites_;
    }
    pyramid.sPrev[idx] = s0;
    pyramid.iPrev[idx] = slice;
}

void SliceWorker::flush() {
    sc_.counters.add(kVolumeSamples, samples_);
    for (int l = 0; l <= sc_.lmax; ++l) sc_.counters.add(kVolumeSamplesLevel, l, samplesPerLevel_[l]);
    sc_.counters.add(kOracleSamples, oracleSamples_);
    sc_.counters.add(kSynthesisOps, syntheses_);
    sc_.counters.add(kCompositeOps, composites_);
}

}  // namespace weft
