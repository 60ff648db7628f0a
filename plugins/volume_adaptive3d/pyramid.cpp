#include "plugins/volume_adaptive3d/pyramid.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace weft {

namespace {

const Counter kOracleSamples{"oracle.samples", "oracle lookups (the paper's SAMPLE ORACLE)"};
const Counter kSynthesisOps{"synthesis.ops", "per-pixel syntheses of data and oracle (the paper's SYNTHESIZE)"};
const IndexedCounter kVolumeSamplesLevel{"volume.samples.level", "volume lookups at pyramid level N"};

// Each volume's background scalar repeated for every pixel, volume-major.
FreshBuffer<float> backgrounds(const std::vector<SliceVolume>& volumes, std::size_t pixels) {
    FreshBuffer<float> s(pixels * volumes.size());
    for (std::size_t k = 0; k < volumes.size(); ++k)
        fillInParallel(s.data() + k * pixels, pixels, float(volumes[k].volume->tf.normalize(volumes[k].volume->grid->background())));
    return s;
}

}  // namespace

Pyramid::Pyramid(const Camera& camera, const std::vector<SliceVolume>& volumes, const SliceSetup& slices, int lmax,
                 int paddedWidth, int paddedHeight, int imageWidth, int imageHeight) {
    const bool emits = sceneEmits(volumes);
    for (int l = 0; l <= lmax; ++l) {
        PyramidLevel level;
        level.rays = makeLevelRays(camera, volumes, slices, l, paddedWidth, paddedHeight, imageWidth, imageHeight);
        level.s = backgrounds(volumes, level.rays.dir.size());
        if (emits) level.e.assign(level.s.size(), Vec3f(0.0f));
        level.d = filledBuffer(level.rays.dir.size(), 1.0f);
        level.tilesX = (level.rays.width + kTile - 1) / kTile;
        level.tilesY = (level.rays.height + kTile - 1) / kTile;
        level.tileDueLevel.assign(std::size_t(level.tilesX) * level.tilesY, 0);
        level.tileQuiet.assign(level.tileDueLevel.size(), 0);
        level.pixelAngle = 2.0 * std::tan(0.5 * camera.fovY * M_PI / 180.0) / imageHeight;
        levels_.push_back(std::move(level));
    }
    const std::size_t n = levels_[0].rays.dir.size();
    sPrev = backgrounds(volumes, n);
    if (emits) ePrev.assign(sPrev.size(), Vec3f(0.0f));
    iPrev = filledBuffer(n, 0);
    color = zeroedBuffer<SegmentCompositor>(n);
    quietComposite.assign(levels_[0].tileQuiet.size(), -1);
}

void Pyramid::setSurfaces(std::vector<double> tHit, const SliceSetup& slices) {
    const int kNone = SurfaceSlices::kNoSurface;
    std::vector<int> k(tHit.size());
    for (std::size_t i = 0; i < tHit.size(); ++i) {
        const double at = (tHit[i] - slices.tNear) / slices.spacing;  // +inf without a surface
        k[i] = at >= slices.imax ? kNone : std::max(-1, int(std::floor(at)));  // beyond the last slice: nothing to cut
    }
    surfaces.tHit = std::move(tHit);
    surfaces.lo.assign(1, k);
    surfaces.hi.assign(1, std::move(k));
    for (std::size_t l = 1; l < levels_.size(); ++l) {
        const LevelRays& fine = levels_[l - 1].rays;
        const LevelRays& coarse = levels_[l].rays;
        std::vector<int> lo(coarse.dir.size()), hi(coarse.dir.size());
        for (int y = 0; y < coarse.height; ++y)
            for (int x = 0; x < coarse.width; ++x) {
                int a = kNone, b = -1;
                for (int c = 0; c < 4; ++c) {
                    const int child = fine.index(2 * x + (c & 1), 2 * y + (c >> 1));
                    a = std::min(a, surfaces.lo[l - 1][child]), b = std::max(b, surfaces.hi[l - 1][child]);
                }
                lo[coarse.index(x, y)] = a, hi[coarse.index(x, y)] = b;
            }
        surfaces.lo.push_back(std::move(lo));
        surfaces.hi.push_back(std::move(hi));
    }
}

Image Pyramid::image(int width, int height) const {
    Image img = Image::rgba(width, height);
    tbb::parallel_for(0, height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const SegmentCompositor& c = color[levels_[0].rays.index(x, y)];
            float* px = img.pixel(x, y);
            px[0] = c.r, px[1] = c.g, px[2] = c.b, px[3] = c.a;
        }
    });
    return img;
}

SliceWorker::SliceWorker(SliceContext& sc) : sc_(sc), data_(sc.volumes), segments_(sc.volumes.size()) {
    for (std::size_t k = 0; k < sc.volumes.size(); ++k) {
        oracleAccessors_.emplace_back(sc.fields[k].accessor());
    }
    emits_ = sceneEmits(sc.volumes);
    data_.setTime(sc.time);
    one_ = sc.volumes.size() == 1 && sc.volumes[0].reference && sc.volumes[0].lengthScale == 1 && !emits_ && !sc.volumes[0].volume->motion;
    sampler0_ = &data_.sampler(0);
    oracle0_ = &oracleAccessors_[0];
    background0_ = data_.background(0);
    tables0_ = &sc.tables.of(sc.volumes[0]);
    quietSkips_ = true;
    for (std::size_t k = 0; k < sc.volumes.size(); ++k)
        for (float fx : {0.25f, 0.75f}) {
            const float bg = data_.background(k), top = (1 - fx) * bg + fx * bg;
            for (float fy : {0.25f, 0.75f}) quietSkips_ = quietSkips_ && (1 - fy) * top + fy * top == bg;
        }
}


// Figures 5-7: bilinear interpolation of the coarser level at this pixel's
// centre, i.e. weights 9/16, 3/16, 3/16, 1/16 of the four nearest parents.
template <bool kOne, bool kSurfaces>
[[gnu::always_inline]] inline void SliceWorker::synthesizeOf(Pyramid& pyramid, int l, int x, int y, int idx, int slice) {
    PyramidLevel& fine = pyramid.level(l);
    const PyramidLevel& coarse = pyramid.level(l + 1);
    const int cw = coarse.rays.width, ch = coarse.rays.height;
    const int x0 = (x - 1) >> 1, y0 = (y - 1) >> 1;                   // parent at or left/above the centre
    const float fx = (x & 1) ? 0.25f : 0.75f, fy = (y & 1) ? 0.25f : 0.75f;  // weight of the second parent
    const int xa = std::clamp(x0, 0, cw - 1), xb = std::clamp(x0 + 1, 0, cw - 1);
    const int ya = std::clamp(y0, 0, ch - 1), yb = std::clamp(y0 + 1, 0, ch - 1);
    auto blend = [&](const auto* v) __attribute__((always_inline)) {  // data and distances (float), emission (Vec3f)
        const auto top = (1 - fx) * v[ya * cw + xa] + fx * v[ya * cw + xb];
        const auto bottom = (1 - fx) * v[yb * cw + xa] + fx * v[yb * cw + xb];
        return (1 - fy) * top + fy * bottom;
    };
    fine.d[idx] = blend(coarse.d.data());
    if constexpr (kOne) {
        fine.s[idx] = blend(coarse.s.data());
    } else {
        const std::size_t fn = fine.rays.dir.size(), cn = coarse.rays.dir.size();
        for (std::size_t k = 0; k < sc_.volumes.size(); ++k) fine.s[k * fn + idx] = blend(coarse.s.data() + k * cn);
        if (emits_)
            for (std::size_t k = 0; k < sc_.volumes.size(); ++k) fine.e[k * fn + idx] = blend(coarse.e.data() + k * cn);
    }
    if constexpr (kSurfaces) fine.d[idx] = surfaceBound(pyramid, l, idx, slice, fine.d[idx]);
    ++syntheses_;
}

float SliceWorker::oracleDistance(int k, const Vec3d& p) {
    const SliceVolume& v = sc_.volumes[k];
    return float(sc_.fields[k].at(oracleAccessors_[k], v.toOwn(p)) / v.lengthScale);
}

template <bool kSurfaces>
[[gnu::always_inline]] inline float SliceWorker::slicesToSkip(const Pyramid& pyramid, int l, int idx, int slice, float dVoxels) const {
    const PyramidLevel& level = pyramid.level(l);
    // The skipping rule counts image-plane and ray distances in one unit
    // (Kraus et al. assume pixels no wider than a slice): where pixels are
    // wider, distances are counted in pixel widths, so a coarse level never
    // skips a feature between its rays.
    const double unit = std::max(sc_.slices.spacing, sc_.slices.t(slice) * level.pixelAngle);
    const float d = std::clamp(float(dVoxels / unit), 1.0f, float(1 << sc_.lmax));
    return kSurfaces ? surfaceBound(pyramid, l, idx, slice, d) : d;
}

// One volume in its own index space: the loop below without its per-volume
// offsets, transforms and minima (the same values, at the cost the
// one-volume renderer had before volumes could overlap).
[[gnu::always_inline]] inline float SliceWorker::sampleOneVolume(PyramidLevel& level, int l, int idx, int slice, const Vec3d& p) {
    const LevelRays& rays = level.rays;
    const int first = rays.first[idx];
    const bool inside = slice >= first && slice <= rays.last[idx];
    float dVoxels = float(sc_.fields[0].at(*oracle0_, p));
    oracleSamples_ += inside || sc_.fields[0].rings;
    if (inside) {
        level.s[idx] = sampler0_->sample(p);
        ++samples_, ++samplesPerLevel_[l];
    } else {
        level.s[idx] = background0_;
        if (slice < first) dVoxels = std::min(dVoxels, float(std::max(1, first - 1 - slice) * sc_.slices.spacing));
    }
    return dVoxels;
}

float SliceWorker::sampleVolumes(PyramidLevel& level, int l, int idx, int slice, const Vec3d& p) {
    const LevelRays& rays = level.rays;
    const int n = int(sc_.volumes.size());
    const std::size_t pixels = rays.dir.size();
    float dInside = std::numeric_limits<float>::infinity(), dAll = dInside, dAhead = dInside;
    for (int k = 0; k < n; ++k) {
        const int first = rays.firstOf(k, idx);
        const bool inside = slice >= first && slice <= rays.lastOf(k, idx);
        float dVoxels = oracleDistance(k, p);
        oracleSamples_ += inside || sc_.fields[k].rings;  // a constant oracle costs nothing outside
        float& s = level.s[k * pixels + idx];
        if (emits_) level.e[k * pixels + idx] = inside ? data_.emission(k, p) : Vec3f(0.0f);
        if (inside) {
            s = data_.sample(k, p);
            ++samples_, ++samplesPerLevel_[l];
            dInside = std::min(dInside, dVoxels);
        } else {
            s = data_.background(k);
            // Before a volume, skip no further than the slice just in front of
            // it, whose background sample starts its first segment.
            if (slice < first) {
                const float ahead = float(std::max(1, first - 1 - slice) * sc_.slices.spacing);
                dVoxels = std::min(dVoxels, ahead), dAhead = std::min(dAhead, ahead);
            }
        }
        dAll = std::min(dAll, dVoxels);
    }
    return dInside < std::numeric_limits<float>::infinity() ? std::min(dInside, dAhead) : dAll;
}

// The oracle is asked on every sample, inside a volume's box or not: a
// coarse ray may still be outside while the finer rays that inherit its
// distance are already inside. With several volumes the distance is the
// smallest of the volumes holding the point (of all of them where none
// does), and never reaches past the start of a volume still ahead.
template <bool kOne, bool kSurfaces>
[[gnu::always_inline]] inline void SliceWorker::sampleOf(Pyramid& pyramid, int l, int idx, int slice) {
    PyramidLevel& level = pyramid.level(l);
    const Vec3d p = sc_.slices.eye + level.rays.dir[idx] * sc_.slices.t(slice);
    const float dVoxels = kOne ? sampleOneVolume(level, l, idx, slice, p) : sampleVolumes(level, l, idx, slice, p);
    level.d[idx] = slicesToSkip<kSurfaces>(pyramid, l, idx, slice, dVoxels);
}

// Skipping never passes a surface: a level-0 pixel is due on its last
// slice in front of its surface (the bound keeps every later due slice at
// or before it), and a coarse pixel on the nearest surface slice of its
// footprint. Where the footprint's surfaces lie at different depths (an
// edge or a slanted wall) the coarse pixel is refined, sampled on every
// slice between them, so no finer pixel is synthesized from samples that
// skipped across the discontinuity.
float SliceWorker::surfaceBound(const Pyramid& pyramid, int l, int idx, int slice, float d) const {
    const int lo = pyramid.surfaces.lo[l][idx], hi = pyramid.surfaces.hi[l][idx];
    if (slice < lo) return std::min(d, float(lo - slice));
    if (slice < hi || (l == 0 && slice == hi)) return 1.0f;
    return d;
}

// One volume: its table set straight, no media to combine.
[[gnu::always_inline]] inline void SliceWorker::compositeOneVolume(Pyramid& pyramid, int idx, int slice) {
    const float s0 = pyramid.level(0).s[idx];
    float& sPrev = pyramid.sPrev[idx];
    if (slice > 0 && !(s0 == background0_ && sPrev == background0_)) {
        pyramid.color[idx].add(tables0_->forSlices(slice - pyramid.iPrev[idx]).lookup(0, sPrev, s0));
        ++composites_;
    }
    sPrev = s0;
}

void SliceWorker::compositeVolumes(Pyramid& pyramid, int idx, int slice) {
    const int n = int(sc_.volumes.size());
    const std::size_t pixels = pyramid.level(0).rays.dir.size();
    const float* s0 = pyramid.level(0).s.data() + idx;
    float* sPrev = pyramid.sPrev.data() + idx;
    const Vec3f* e0 = emits_ ? pyramid.level(0).e.data() + idx : nullptr;
    Vec3f* ePrev = emits_ ? pyramid.ePrev.data() + idx : nullptr;
    bool empty = true;
    for (int k = 0; k < n; ++k) {
        const float bg = data_.background(k);
        segments_[k] = {0, 0, 0, 0};
        const bool glows = emits_ && (e0[k * pixels] != Vec3f(0.0f) || ePrev[k * pixels] != Vec3f(0.0f));
        if (s0[k * pixels] == bg && sPrev[k * pixels] == bg && !glows) continue;
        empty = false;
        if (slice > 0) {
            const int length = slice - pyramid.iPrev[idx];
            const PreintegrationTable& table = sc_.tables.of(sc_.volumes[k]).forSlices(length);
            segments_[k] = table.lookup(0, sPrev[k * pixels], s0[k * pixels]);
            if (glows) addEmission(segments_[k], table.lookupEmission(0, sPrev[k * pixels], s0[k * pixels]), ePrev[k * pixels], e0[k * pixels]);
        }
    }
    if (slice > 0 && !empty) {
        pyramid.color[idx].add(combineMedia(segments_.data(), n));
        ++composites_;
    }
    for (int k = 0; k < n; ++k) sPrev[k * pixels] = s0[k * pixels];
    if (emits_)
        for (int k = 0; k < n; ++k) ePrev[k * pixels] = e0[k * pixels];
}

// Figure 8: the segment from the previous composite to this slice. A
// segment with background at both ends adds nothing (the transfer function
// is transparent there), so it costs no table lookup; overlapping volumes'
// segments combine as media whose extinctions add (combineMedia).
template <bool kOne, bool kSurfaces>
[[gnu::always_inline]] inline void SliceWorker::compositeOf(Pyramid& pyramid, int idx, int slice) {
    if constexpr (kOne) compositeOneVolume(pyramid, idx, slice);
    else compositeVolumes(pyramid, idx, slice);
    pyramid.iPrev[idx] = slice;
    if constexpr (kSurfaces)
        if (slice == pyramid.surfaces.lo[0][idx]) compositeToSurface(pyramid, idx, slice);
}

// Dispatch on what the scene holds, so that the per-pixel code below is
// compiled once per case with no test of it inside the loops.
template <typename F>
decltype(auto) SliceWorker::dispatch(const Pyramid& pyramid, F&& f) {
    const bool surfaces = pyramid.surfaces.any();
    if (one_) return surfaces ? f(Case<true, true>{}) : f(Case<true, false>{});
    return surfaces ? f(Case<false, true>{}) : f(Case<false, false>{});
}

std::uint8_t SliceWorker::tile(Pyramid& pyramid, int l, int lslice, int slice, int tx, int ty) {
    return dispatch(pyramid, [&](auto c) { return tileOf<c.one, c.surfaces>(pyramid, l, lslice, slice, tx, ty); });
}

void SliceWorker::synthesize(Pyramid& pyramid, int l, int x, int y, int idx, int slice) {
    dispatch(pyramid, [&](auto c) { synthesizeOf<c.one, c.surfaces>(pyramid, l, x, y, idx, slice); });
}

void SliceWorker::sample(Pyramid& pyramid, int l, int idx, int slice) {
    dispatch(pyramid, [&](auto c) { sampleOf<c.one, c.surfaces>(pyramid, l, idx, slice); });
}

void SliceWorker::composite(Pyramid& pyramid, int idx, int slice) {
    dispatch(pyramid, [&](auto c) { compositeOf<c.one, c.surfaces>(pyramid, idx, slice); });
}

[[gnu::always_inline]] inline bool SliceWorker::pixelQuiet(const Pyramid& pyramid, int l, int idx) const {
    const PyramidLevel& level = pyramid.level(l);
    if (level.d[idx] != float(1 << sc_.lmax)) return false;
    const std::size_t pixels = level.rays.dir.size();
    for (std::size_t k = 0; k < sc_.volumes.size(); ++k) {
        const std::size_t i = k * pixels + idx;
        const float bg = data_.background(int(k));
        if (level.s[i] != bg || (emits_ && level.e[i] != Vec3f(0.0f))) return false;
        if (l == 0 && (pyramid.sPrev[i] != bg || (emits_ && pyramid.ePrev[i] != Vec3f(0.0f)))) return false;
    }
    return true;
}

bool SliceWorker::staysQuiet(const Pyramid& pyramid, int l, int tx, int ty) const {
    const PyramidLevel& level = pyramid.level(l);
    if (!level.tileQuiet[std::size_t(ty) * level.tilesX + tx]) return false;
    // The tile's pixels read coarse pixels (4 tx - 1) .. (4 tx + 4), clamped; likewise in y.
    const PyramidLevel& coarse = pyramid.level(l + 1);
    const int cx0 = std::max(0, (kTile / 2 * tx - 1) / kTile), cx1 = std::min(coarse.tilesX - 1, (kTile / 2 * tx + kTile / 2) / kTile);
    const int cy0 = std::max(0, (kTile / 2 * ty - 1) / kTile), cy1 = std::min(coarse.tilesY - 1, (kTile / 2 * ty + kTile / 2) / kTile);
    for (int cy = cy0; cy <= cy1; ++cy)
        for (int cx = cx0; cx <= cx1; ++cx)
            if (!coarse.tileQuiet[std::size_t(cy) * coarse.tilesX + cx]) return false;
    return true;
}

template <bool kOne, bool kSurfaces>
std::uint8_t SliceWorker::tileOf(Pyramid& pyramid, int l, int lslice, int slice, int tx, int ty) {
    PyramidLevel& level = pyramid.level(l);
    const std::size_t tile = std::size_t(ty) * level.tilesX + tx;
    const int x0 = tx * kTile, y0 = ty * kTile;
    const int x1 = std::min(level.rays.width, x0 + kTile), y1 = std::min(level.rays.height, y0 + kTile);
    // A quiet tile is due on full slices only; where its parents are quiet
    // too, synthesis would give its pixels the values they hold and their
    // segments hold only background: nothing to visit but the composite's slice.
    if (!kSurfaces && l < sc_.lmax && quietSkips_ && staysQuiet(pyramid, l, tx, ty)) {
        if (l == 0) pyramid.quietComposite[tile] = slice;
        return std::uint8_t(sc_.lmax);
    }
    if (l == 0 && pyramid.quietComposite[tile] >= 0) {
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) pyramid.iPrev[level.rays.index(x, y)] = pyramid.quietComposite[tile];
        pyramid.quietComposite[tile] = -1;
    }
    const float sampleBelow = float(2 << l);  // 2^(l+1)
    std::uint8_t minDue = 255;
    bool quiet = !kSurfaces;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const int idx = level.rays.index(x, y);
            if (kSurfaces && l == 0 && slice > pyramid.surfaces.lo[0][idx]) {  // behind its surface: nothing left to do
                level.d[idx] = float(1 << sc_.lmax);
                minDue = std::min(minDue, dueLevel(level.d[idx]));
                continue;
            }
            if (l < lslice && isDue(level.d[idx], lslice, sc_.lmax)) synthesizeOf<kOne, kSurfaces>(pyramid, l, x, y, idx, slice);
            const float d = level.d[idx];
            const bool accumulate = l == 0 && isDue(d, lslice, sc_.lmax);
            if (l == sc_.lmax || d < sampleBelow) sampleOf<kOne, kSurfaces>(pyramid, l, idx, slice);
            if (accumulate) compositeOf<kOne, kSurfaces>(pyramid, idx, slice);
            minDue = std::min(minDue, dueLevel(level.d[idx]));
            if (!kSurfaces) quiet = quiet && pixelQuiet(pyramid, l, idx);
        }
    level.tileQuiet[tile] = quiet;
    return minDue;
}

// The segment the surface cuts, from this slice to the surface, with its
// true length (exact, as volume.preint does), its back scalars read at the surface.
void SliceWorker::compositeToSurface(Pyramid& pyramid, int idx, int slice) {
    const double tHit = pyramid.surfaces.tHit[idx], length = tHit - sc_.slices.t(slice);
    if (!(length > 0)) return;
    const Vec3d p = sc_.slices.eye + pyramid.level(0).rays.dir[idx] * tHit;
    const std::size_t pixels = pyramid.level(0).rays.dir.size();
    const int n = int(sc_.volumes.size());
    const PyramidLevel& level0 = pyramid.level(0);
    for (int k = 0; k < n; ++k)
        segments_[k] = emits_ ? exactEmittingSegment(sc_.volumes[k], level0.s[k * pixels + idx], data_.sample(k, p), level0.e[k * pixels + idx],
                                                     data_.emission(k, p), length)
                              : exactSegment(sc_.volumes[k], level0.s[k * pixels + idx], data_.sample(k, p), length);
    samples_ += n, samplesPerLevel_[0] += n;
    pyramid.color[idx].add(combineMedia(segments_.data(), n));
    ++composites_;
}

void SliceWorker::flush() {
    sc_.counters.add(kVolumeSamples, samples_);
    for (int l = 0; l <= sc_.lmax; ++l) sc_.counters.add(kVolumeSamplesLevel, l, samplesPerLevel_[l]);
    sc_.counters.add(kOracleSamples, oracleSamples_);
    sc_.counters.add(kSynthesisOps, syntheses_);
    sc_.counters.add(kCompositeOps, composites_);
}

}  // namespace weft
