#include "plugins/volume_raymarch/volume_march.hpp"

#include "core/base/shared_cache.hpp"
#include "core/volume/skip/visible_cells.hpp"
#include "core/volume/volume_key.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace weft {

namespace {

// Adds b's extinction to a's and makes a's colour the extinction-weighted
// mean: overlapping emission-absorption media add both.
void mergeInto(TfSample& a, const TfSample& b) {
    const float e = a.extinction + b.extinction;
    a.r = (a.r * a.extinction + b.r * b.extinction) / e;
    a.g = (a.g * a.extinction + b.g * b.extinction) / e;
    a.b = (a.b * a.extinction + b.b * b.extinction) / e;
    a.extinction = e;
}

// Length-weighted emission of a segment: (1 - exp(-s L)) / s, which tends
// to L as s L -> 0 (where the quotient would lose its digits).
float emissionLength(float extinction, float length, float alpha) {
    const float depth = extinction * length;
    return depth > 1e-4f ? alpha / extinction : length * (1.0f - 0.5f * depth);
}

void addEmitting(RayAccumulator& acc, const TfSample& s, float alpha, const openvdb::Vec3s& e, float length) {
    const float w = emissionLength(s.extinction, length, alpha);
    acc.addPremultiplied(s.r * alpha + e[0] * w, s.g * alpha + e[1] * w, s.b * alpha + e[2] * w, alpha);
}

}  // namespace

EmptySpaceSkipper::EmptySpaceSkipper(const std::vector<Volume>& volumes) {
    double filled = 0, boxed = 0;
    for (const Volume& v : volumes) {
        openvdb::FloatGrid::Ptr visible = visibleCells(*v.grid, v.tf);
        cells_.push_back(v.emission || v.motion ? nullptr : visible);
        indexGrids_.push_back(occupancyIndexGrid(v, visible));
        // A sample lies in the leaf of its cell's low corner, so visible cells
        // alone need no dilation; one voxel keeps a margin for the HDDA's
        // rounding at leaf faces. An emission voxel's trilinear support reaches
        // its 26 neighbours: three face-neighbour dilations cover them all.
        // A volume its transfer function hides whole has no intersector (OpenVDB's refuses an empty grid).
        const bool shows = indexGrids_.back()->tree().activeVoxelCount() > 0;
        blocks_.push_back(cells_.back() && shows ? VisibleBlocks::of(*cells_.back()) : nullptr);
        const int dilation = cells_.back() ? 1 : 3;
        const bool hdda = shows && !blocks_.back();
        intersectors_.push_back(hdda ? std::make_unique<VolumeIntersector>(*indexGrids_.back(), dilation) : nullptr);
        if (v.empty()) continue;
        const openvdb::FloatTree& tree = indexGrids_.back()->tree();
        filled += double(tree.leafCount()) * double(openvdb::FloatTree::LeafNodeType::SIZE);
        auto tiles = tree.cbeginValueOn();
        tiles.setMaxDepth(openvdb::FloatTree::ValueOnCIter::LEAF_DEPTH - 1);  // tiles, not voxels
        for (; tiles; ++tiles) filled += double(tiles.getVoxelCount());
        boxed += double(v.activeBox.volume());
    }
    pays_ = boxed > 0 && filled <= 0.75 * boxed;
}

std::optional<ScreenFootprint> EmptySpaceSkipper::footprint(const std::vector<Volume>& volumes, const CameraRays& rays, int width,
                                                           int height) const {
    ScreenFootprint out(rays, width, height);
    for (std::size_t i = 0; i < volumes.size(); ++i) {
        if (volumes[i].empty() || (cells_[i] && !blocks_[i] && !intersectors_[i])) continue;  // adds nothing to any ray
        if (!blocks_[i]) return std::nullopt;
        out.addBlocks(*blocks_[i], volumes[i].grid->transform());
    }
    return out;
}

namespace {

SharedCache<std::shared_ptr<const EmptySpaceSkipper>>& skippers() {
    static SharedCache<std::shared_ptr<const EmptySpaceSkipper>> entries(kSkipperCacheEntries);
    return entries;
}

}  // namespace

SharedSkipper sharedEmptySpaceSkipper(const std::vector<Volume>& volumes) {
    const auto build = [&] { return std::make_shared<const EmptySpaceSkipper>(volumes); };
    const bool moves = std::any_of(volumes.begin(), volumes.end(), [](const Volume& v) { return v.motion != nullptr; });
    if (moves) return {build(), false};
    std::string key;
    std::vector<std::shared_ptr<const void>> kept;
    for (const Volume& v : volumes) key += volumeKey(v) + "#", kept.push_back(keptGrid(v));
    auto found = skippers().get(key, build, std::move(kept));
    return {std::move(found.value), found.reused};
}

void clearSkipperCache() { skippers().clear(); }

constexpr double kSkipMotionReach = 16;

bool emptySpaceSkippable(const std::vector<Volume>& volumes) {
    bool any = false;
    for (const Volume& v : volumes) {
        if (v.empty()) continue;
        if (v.motion && v.motionReach > kSkipMotionReach) return false;  // dilating by the reach would cost more than it saves
        const float background = v.grid->background();
        if (!v.tf.transparentOver(background, background)) return false;
        any = true;
    }
    return any;
}

bool emptySpacePays(const std::vector<Volume>& volumes) {
    return emptySpaceSkippable(volumes) && EmptySpaceSkipper(volumes).pays();
}

VolumeMarcher::Lookup::Lookup(const Volume& v, const EmptySpaceSkipper* skipper, std::size_t index)
    : volume(v), accessor(v.grid->getConstAccessor()), sampler(accessor, v.grid->transform()),
      voxelLength(v.voxelLength()), uniform(v.grid->transform().hasUniformScale()) {
    if (v.emission) {
        emissionAccessor.emplace(v.emission->getConstAccessor());
        emission.emplace(*emissionAccessor, v.emission->transform());
    }
    emplaceMotion(motion, v);
    if (!skipper) return;
    if (const VolumeIntersector* prototype = skipper->of(index)) hdda.emplace(*prototype);
    blocks = skipper->blocks(index);
    if (const openvdb::FloatGrid* cells = skipper->cells(index); cells && !blocks) visible.emplace(*cells);
}

VolumeMarcher::VolumeMarcher(const Scene& scene, const MarchSettings& settings, const EmptySpaceSkipper* skipper)
    : settings_(settings), skipping_(skipper != nullptr) {
    for (std::size_t i = 0; i < scene.volumes.size(); ++i) {
        lookups_.emplace_back(scene.volumes[i], skipper, i);
        if (i < settings.dense.size()) lookups_.back().sampler.useDense(settings.dense[i]);
    }
}

// The volumes this ray crosses, their index rays and the march's unit.
bool VolumeMarcher::cross(const Ray& ray) {
    crossings_.clear();
    moving_ = false;
    unitLength_ = std::numeric_limits<double>::max();
    if (settings_.bounds) settings_.bounds->query(ray.origin, ray.dir, std::numeric_limits<double>::infinity(), crossed_);
    const std::size_t n = settings_.bounds ? crossed_.size() : lookups_.size();
    for (std::size_t k = 0; k < n; ++k) {
        Lookup& l = lookups_[settings_.bounds ? crossed_[k] : k];
        const auto r = toIndexRay(ray, l.volume);
        if (!r) continue;
        crossings_.push_back({&l, *r, 0, 0});
        if (l.motion && time_ != 0) moving_ = true;
        unitLength_ = std::min(unitLength_, l.voxelLength);
    }
    if (crossings_.empty()) return false;
    const double speed = ray.dir.length();  // world length per unit of the ray's parameter
    u0_ = std::numeric_limits<double>::max(), uEnd_ = 0;
    for (Crossing& c : crossings_) {
        const double scale = unitLength_ / c.lookup->voxelLength;  // exactly 1 for the finest volume
        c.perU = c.lookup->uniform ? scale : c.ray.speed * unitLength_ / speed;
        c.depthScale = float(scale);
        u0_ = std::min(u0_, c.ray.t0 / c.perU);
        uEnd_ = std::max(uEnd_, c.ray.t1 / c.perU);
    }
    return true;
}

// Where samples may be needed, in march units: the whole span, or with
// skip_empty each volume's occupied intervals (overlapping ones merged).
void VolumeMarcher::collectIntervals(double uEnd) {
    intervals_.clear();
    if (!skipping_) {
        intervals_.push_back({u0_, uEnd});
        return;
    }
    for (const Crossing& c : crossings_) {
        if (c.lookup->blocks) {
            IndexRay within = c.ray;  // index t = world t x speed
            within.t0 = std::max(within.t0, blocksFrom_ * c.ray.speed), within.t1 = std::min(within.t1, blocksTo_ * c.ray.speed);
            if (within.t0 <= within.t1) c.lookup->blocks->intervals(within, c.perU, intervals_);
            continue;
        }
        if (!c.lookup->hdda) continue;  // its transfer function hides it whole
        VolumeIntersector& hdda = *c.lookup->hdda;
        if (!hdda.setIndexRay(openvdb::math::Ray<double>(c.ray.origin, c.ray.dir, c.ray.t0, c.ray.t1))) continue;
        double a = 0, b = 0;
        while (hdda.march(a, b)) intervals_.push_back({a / c.perU, b / c.perU});
    }
    if (crossings_.size() == 1) return;  // one HDDA's intervals are already in order
    mergeIntervals(intervals_);
}

// One segment of `length` march units sampled at u: every volume holding u.
void VolumeMarcher::addSegment(double u, double length, RayAccumulator& acc) {
    TfSample sum{0, 0, 0, 0};
    openvdb::Vec3s glow(0.0f);  // emission per march unit
    bool any = false;
    for (Crossing& c : crossings_) {
        const double t = u * c.perU;
        if (t < c.ray.t0 || t >= c.ray.t1) continue;
        Vec3d p = c.ray.at(t);
        if (c.lookup->motion && time_ != 0) p = c.lookup->motion->advected(p, time_);
        if (!c.lookup->shows(p)) continue;  // zero extinction, no emission: adds nothing
        const float value = c.lookup->sampler.isSample(p);
        ++samples_;
        if (c.lookup->emission) glow += c.lookup->emission->isSample(p) * c.depthScale;
        TfSample s = c.lookup->volume.tf.lookup(value);
        if (!(s.extinction > 0)) continue;  // adds nothing
        s.extinction *= c.depthScale;
        if (any) mergeInto(sum, s);
        else sum = s, any = true;
    }
    const float alpha = any ? segmentOpacity(sum.extinction, float(length)) : 0.0f;
    if (glow != openvdb::Vec3s(0.0f)) addEmitting(acc, sum, alpha, glow, float(length));
    else if (any) acc.add(sum, alpha);
}

// One emitting volume: addSegment's arithmetic with its lookups hoisted.
bool VolumeMarcher::marchEmitting(const RayInterval& in, double kMax, float offset, RayAccumulator& acc) {
    const Crossing& c = crossings_.front();
    VolumeSampler& sampler = c.lookup->sampler;
    Vec3LeafSampler& emission = *c.lookup->emission;
    const TransferFunction& tf = c.lookup->volume.tf;
    std::int64_t n = 0;
    const bool more = marchSteps(in, kMax, offset, acc, [&](double u, double h) {
        const Vec3d p = c.ray.at(u * c.perU);
        TfSample s = tf.lookup(sampler.isSample(p));
        s.extinction = std::max(s.extinction, 0.0f) * c.depthScale;
        ++n;
        addEmitting(acc, s, segmentOpacity(s.extinction, float(h)), emission.isSample(p) * c.depthScale, float(h));
    });
    samples_ += n;
    return more;
}

// Samples u_k = u0 + (k + offset) * step for k < kMax inside [lo, hi);
// false once early ray termination ends the ray.
template <class AddSegment>
bool VolumeMarcher::marchSteps(const RayInterval& in, double kMax, float offset, RayAccumulator& acc, AddSegment&& add) {
    const double h = settings_.step, u0 = u0_, end = std::min(in.hi, uEnd_);  // locals: no reloads after each sample
    const float ert = settings_.ertOpacity;
    const double kFirst = std::max(0.0, std::ceil((in.lo - u0) / h - offset));
    for (double k = kFirst; k < kMax; k += 1.0) {
        const double u = u0 + (k + offset) * h;
        if (u >= end) break;
        add(u, h);
        if (acc.opacity() >= ert) return false;
    }
    return true;
}

bool VolumeMarcher::marchInterval(const RayInterval& in, double kMax, float offset, RayAccumulator& acc) {
    if (crossings_.size() > 1 || moving_) return marchSteps(in, kMax, offset, acc, [&](double u, double h) { addSegment(u, h, acc); });
    if (crossings_.front().lookup->emission) return marchEmitting(in, kMax, offset, acc);
    // One volume, the common case: the march's bounds keep every sample inside it.
    const IndexRay ray = crossings_.front().ray;
    const double perU = crossings_.front().perU;
    const float depthScale = crossings_.front().depthScale;
    VolumeSampler& sampler = crossings_.front().lookup->sampler;
    const TransferFunction& tf = crossings_.front().lookup->volume.tf;
    std::int64_t n = 0;
    const auto sample = [&](const Vec3d& p, double h) {
        const TfSample s = tf.lookup(sampler.isSample(p));
        ++n;
        if (s.extinction > 0) acc.add(s, segmentOpacity(s.extinction * depthScale, float(h)));  // else it adds nothing
    };
    bool more;
    // A hidden cell's sample has zero extinction: it adds nothing.
    if (const VisibleBlocks* blocks = crossings_.front().lookup->blocks)
        more = marchSteps(in, kMax, offset, acc, [&](double u, double h) {
            const Vec3d p = ray.at(u * perU);
            if (blocks->cellVisible(p)) sample(p, h);
        });
    else if (auto& visible = crossings_.front().lookup->visible)
        more = marchSteps(in, kMax, offset, acc, [&](double u, double h) {
            const Vec3d p = ray.at(u * perU);
            if ((*visible)(p)) sample(p, h);
        });
    else
        more = marchSteps(in, kMax, offset, acc, [&](double u, double h) { sample(ray.at(u * perU), h); });
    samples_ += n;
    return more;
}

RayAccumulator VolumeMarcher::march(const Ray& ray, double tSurface, float offset, double time, double t0, double t1) {
    RayAccumulator acc;
    time_ = time;
    blocksFrom_ = t0, blocksTo_ = t1;
    if (!cross(ray)) return acc;
    const double h = settings_.step;
    const double uHit = std::isfinite(tSurface) ? tSurface * ray.dir.length() / unitLength_ : uEnd_;
    if (uHit <= u0_) return acc;
    const bool cut = uHit < uEnd_;  // the surface ends the march inside the volumes
    const double kLast = cut ? std::floor((uHit - u0_) / h) : std::numeric_limits<double>::infinity();
    collectIntervals(uEnd_);
    for (const RayInterval& in : intervals_) {
        if (skipping_ && acc.opacity() >= settings_.ertOpacity) return acc;
        if (!marchInterval(in, kLast, offset, acc)) return acc;
    }
    if (!cut) return acc;
    const double start = u0_ + kLast * h, length = uHit - start;
    if (length > 0) addSegment(start + offset * length, length, acc);
    return acc;
}

}  // namespace weft
