#pragma once
// The volumes of a slice renderer (volume.preint, volume.adaptive3d).
// Slices are measured in the first volume's index space, the reference:
// every other volume is sampled through the affine map from the reference
// index space to its own, and its segment lengths scale by its voxels per
// reference voxel (the ratio of voxel lengths, core/volume/volume.hpp), so
// its transfer function keeps meaning "per voxel of its own". That ratio is
// exact for placements that scale uniformly; an anisotropic placement gets
// its mean voxel length.
#include <deque>
#include <memory>
#include <vector>

#include "core/base/run/counters.hpp"
#include "core/volume/optics/segment_tables.hpp"
#include "core/volume/slice/slice_renderer.hpp"
#include "core/volume/volume_motion.hpp"

namespace weft {

struct SliceVolume {
    const Volume* volume = nullptr;
    bool reference = true;      // the first volume: its own index space
    Vec3d origin{0, 0, 0};      // reference index -> own index: origin + sum p_i axis_i
    Vec3d axis[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    double lengthScale = 1;     // own voxels per reference voxel along a ray
    int tables = 0;             // which SliceTables entry serves it

    Vec3d toOwn(const Vec3d& p) const {
        return reference ? p : origin + axis[0] * p.x() + axis[1] * p.y() + axis[2] * p.z();
    }
};

// Volumes with an equal transfer function and length scale share one table set.
std::vector<SliceVolume> makeSliceVolumes(const std::vector<Volume>& volumes);

// Tables that hold emission weights, counted by both slice techniques
// (emitting scenes only).
extern const Counter kEmissionTables;

// Whether any of the volumes emits (Volume::emission).
bool sceneEmits(const std::vector<SliceVolume>& volumes);

// Pre-integration tables per distinct (transfer function, length scale),
// built lazily per segment length: a volume's tables are built once. A set
// serving an emitting volume also holds emission weights; no other does.
class SliceTables {
public:
    SliceTables(const std::vector<SliceVolume>& volumes, double spacing, int maxSlices, int resolution, PreintPrecision precision);
    SegmentTables& of(const SliceVolume& v) { return *sets_[v.tables]; }
    int builtCount() const;
    int emissionBuiltCount() const;  // of those, the ones holding emission weights
    std::int64_t entriesBuilt() const;  // table entries integrated, over every table

private:
    std::vector<std::unique_ptr<SegmentTables>> sets_;
};

// Trilinear lookups of an emission grid (radiance per voxel length).
class EmissionSampler {
public:
    explicit EmissionSampler(const openvdb::Vec3SGrid& grid) : accessor_(grid.getConstAccessor()), sampler_(accessor_, grid.transform()) {}
    Vec3f sample(const Vec3d& indexPos) const { return sampler_.isSample(indexPos); }

private:
    openvdb::Vec3SGrid::ConstAccessor accessor_;
    mutable Vec3LeafSampler sampler_;  // keeps the last leaf: one per thread
};

// Trilinear lookups of every volume at reference index positions, of its
// data and of its emission where it emits (deques: samplers hold accessors
// by reference and must not move). A moving volume (Volume::motion) is read
// where its velocity advects the point from at the current shutter time
// (setTime; core/volume/volume_motion.hpp), its data and emission alike.
class SliceSamplers {
public:
    explicit SliceSamplers(const std::vector<SliceVolume>& volumes)
        : volumes_(volumes), emitting_(volumes.size(), nullptr), moving_(volumes.size(), nullptr) {
        for (const SliceVolume& v : volumes) samplers_.emplace_back(*v.volume);
        for (std::size_t k = 0; k < volumes.size(); ++k) {
            if (volumes[k].volume->emission) emitting_[k] = &emission_.emplace_back(*volumes[k].volume->emission);
            if (volumes[k].volume->motion) moving_[k] = &motion_.emplace_back(*volumes[k].volume->motion);
        }
    }
    // The shutter time, frames from the frame, of the lookups that follow.
    void setTime(double time) { time_ = time; }
    float sample(int k, const Vec3d& refIndexPos) const { return samplers_[k].sample(own(k, refIndexPos)); }
    bool emits(int k) const { return emitting_[k] != nullptr; }
    // Volume k's emission at a reference index position (zero where it emits nothing).
    Vec3f emission(int k, const Vec3d& refIndexPos) const {
        return emitting_[k] ? emitting_[k]->sample(own(k, refIndexPos)) : Vec3f(0.0f);
    }
    float background(int k) const { return samplers_[k].background(); }
    const ScalarSampler& sampler(int k) const { return samplers_[k]; }
    int size() const { return int(samplers_.size()); }

private:
    // Where volume k is read for a reference position: its own index space, advected when it moves.
    Vec3d own(int k, const Vec3d& refIndexPos) const {
        const Vec3d p = volumes_[k].toOwn(refIndexPos);
        return moving_[k] ? moving_[k]->advected(p, time_) : p;
    }

    const std::vector<SliceVolume>& volumes_;
    std::deque<ScalarSampler> samplers_;
    std::deque<EmissionSampler> emission_;
    std::vector<const EmissionSampler*> emitting_;  // per volume, null where it emits nothing
    std::deque<MotionLookup> motion_;
    std::vector<MotionLookup*> moving_;  // per volume, null where it stays still
    double time_ = 0;
};

// Adds the emission of a segment whose ends emit eFront and eBack (radiance
// per own voxel length) to its premultiplied colour (preintegration.hpp).
inline void addEmission(PreintSample& s, const EmissionWeights& w, const Vec3f& eFront, const Vec3f& eBack) {
    s.r += eFront[0] * w.front + eBack[0] * w.back;
    s.g += eFront[1] * w.front + eBack[1] * w.back;
    s.b += eFront[2] * w.front + eBack[2] * w.back;
}

// The exact segment of `length` reference voxels through volume v.
inline PreintSample exactSegment(const SliceVolume& v, float sFront, float sBack, double length) {
    return PreintegrationTable::integrateSegment(v.volume->tf, sFront, sBack, length * v.lengthScale);
}

// The same with the emission eFront, eBack at its ends.
inline PreintSample exactEmittingSegment(const SliceVolume& v, float sFront, float sBack, const Vec3f& eFront, const Vec3f& eBack,
                                         double length) {
    PreintSample s = exactSegment(v, sFront, sBack, length);
    addEmission(s, PreintegrationTable::integrateEmission(v.volume->tf, sFront, sBack, length * v.lengthScale), eFront, eBack);
    return s;
}

}  // namespace weft
