#pragma once
// What the slice-based volume techniques (volume.preint, volume.adaptive3d)
// share: their common parameters, the scene checks, and sampling the data
// at a point of a slice as a normalised scalar.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/base/params.hpp"
#include "core/scene/scene.hpp"
#include "core/volume/leaf_sampler.hpp"
#include "core/volume/preintegration.hpp"

namespace weft {

struct SliceParams {
    double spacing;  // voxels between slices
    int tableResolution;
    PreintPrecision precision;
};

// spacing, table_res, table_precision.
std::vector<ParamSpec> sliceParamSpecs();
SliceParams readSliceParams(const ParamSet& p);

// One or more volumes whose transfer functions are transparent at their
// background values (samples outside a volume read as its background, as in
// the paper); returns the first, the reference of the slices.
const Volume& requireSliceableVolume(const Scene& scene, const std::string& technique);

// Trilinear data lookups returning s = tf.normalize(value).
class ScalarSampler {
public:
    explicit ScalarSampler(const Volume& volume)
        : accessor_(volume.grid->getConstAccessor()), sampler_(accessor_, volume.grid->transform()),
          background_(float(volume.tf.normalize(volume.grid->background()))), rangeMin_(volume.tf.rangeMin()),
          rangeWidth_(volume.tf.rangeMax() - volume.tf.rangeMin()) {}
    // TransferFunction::normalize, inline: the slice loops call it per sample.
    float sample(const openvdb::Vec3d& indexPos) const {
        const double value = sampler_.isSample(indexPos);
        if (!std::isfinite(value)) return 0.0f;  // NaN voxels read as empty
        return float(std::clamp((value - rangeMin_) / rangeWidth_, 0.0, 1.0));
    }
    float background() const { return background_; }

private:
    using Accessor = openvdb::FloatGrid::ConstAccessor;
    Accessor accessor_;
    mutable LeafSampler sampler_;  // keeps the last leaf: one per thread
    float background_;
    double rangeMin_, rangeWidth_;
};

}  // namespace weft
