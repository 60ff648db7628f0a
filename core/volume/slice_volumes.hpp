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

#include "core/volume/segment_tables.hpp"
#include "core/volume/slice_renderer.hpp"

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

// Pre-integration tables per distinct (transfer function, length scale),
// built lazily per segment length: a volume's tables are built once.
class SliceTables {
public:
    SliceTables(const std::vector<SliceVolume>& volumes, double spacing, int maxSlices, int resolution, PreintPrecision precision);
    SegmentTables& of(const SliceVolume& v) { return *sets_[v.tables]; }
    int builtCount() const;

private:
    std::vector<std::unique_ptr<SegmentTables>> sets_;
};

// Trilinear lookups of every volume at reference index positions (a deque:
// samplers hold accessors by reference and must not move).
class SliceSamplers {
public:
    explicit SliceSamplers(const std::vector<SliceVolume>& volumes) : volumes_(volumes) {
        for (const SliceVolume& v : volumes) samplers_.emplace_back(*v.volume);
    }
    float sample(int k, const Vec3d& refIndexPos) const { return samplers_[k].sample(volumes_[k].toOwn(refIndexPos)); }
    float background(int k) const { return samplers_[k].background(); }
    const ScalarSampler& sampler(int k) const { return samplers_[k]; }
    int size() const { return int(samplers_.size()); }

private:
    const std::vector<SliceVolume>& volumes_;
    std::deque<ScalarSampler> samplers_;
};

// The exact segment of `length` reference voxels through volume v.
inline PreintSample exactSegment(const SliceVolume& v, float sFront, float sBack, double length) {
    return PreintegrationTable::integrateSegment(v.volume->tf, sFront, sBack, length * v.lengthScale);
}

}  // namespace weft
