#pragma once
// What the slice-based volume techniques (volume.preint, volume.adaptive3d)
// share: their common parameters, the scene checks, and sampling the data
// at a point of a slice as a normalised scalar.
#include <vector>

#include "core/base/options/params.hpp"
#include "core/scene/scene.hpp"
#include "core/volume/grid/leaf_sampler.hpp"
#include "core/volume/optics/preintegration.hpp"

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
        : normalize_(volume.tf.normalization()), accessor_(volume.grid->getConstAccessor()),
          sampler_(accessor_, volume.grid->transform()), background_(float(normalize_(volume.grid->background()))) {}
    float sample(const openvdb::Vec3d& indexPos) const { return float(normalize_(sampler_.isSample(indexPos))); }
    float background() const { return background_; }

private:
    using Accessor = openvdb::FloatGrid::ConstAccessor;
    TransferFunction::Normalization normalize_;
    Accessor accessor_;
    mutable LeafSampler sampler_;  // keeps the last leaf: one per thread
    float background_;
};

}  // namespace weft
