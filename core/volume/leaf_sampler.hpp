#pragma once
// Trilinear lookups of a float grid exactly as openvdb::tools::BoxSampler
// makes them (the same eight values, the same arithmetic: images do not
// change), with the eight values read straight from the leaf that holds
// them whenever one leaf does (343 of a leaf's 512 cells). The leaf of the
// last lookup is kept: a ray's consecutive samples mostly stay in one 8^3
// leaf, and the accessor's eight getValue calls per sample were most of a
// march's time. One sampler per thread, like the accessor it reads through.
#include <climits>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

namespace weft {

class LeafSampler {
public:
    using Accessor = openvdb::FloatGrid::ConstAccessor;

    // Reads through `accessor` and maps world points with `transform`; both must outlive the sampler.
    LeafSampler(const Accessor& accessor, const openvdb::math::Transform& transform) : acc_(&accessor), xf_(&transform) {}

    // At an index-space point.
    float isSample(const openvdb::Vec3d& p) {
        const openvdb::Vec3i i = openvdb::tools::local_util::floorVec3(p);
        const openvdb::Vec3d uvw = p - i;
        float v[2][2][2];
        if ((i.x() & 7) != 7 && (i.y() & 7) != 7 && (i.z() & 7) != 7) fromLeaf(i, v);
        else openvdb::tools::BoxSampler::getValues(v, *acc_, openvdb::Coord(i));  // the cell straddles leaves
        return openvdb::tools::BoxSampler::trilinearInterpolation(v, uvw);
    }
    // At a world-space point.
    float wsSample(const openvdb::Vec3d& p) { return isSample(xf_->worldToIndex(p)); }

private:
    void fromLeaf(const openvdb::Vec3i& i, float (&v)[2][2][2]) {
        const openvdb::Coord origin(i.x() & ~7, i.y() & ~7, i.z() & ~7);
        if (origin != origin_) {
            origin_ = origin;
            const auto* leaf = acc_->probeConstLeaf(origin);
            data_ = leaf ? leaf->buffer().data() : nullptr;
            // No leaf: one tile (or the background) covers the leaf's whole region.
            if (!data_) constant_ = acc_->getValue(origin);
        }
        if (!data_) {
            for (auto& plane : v)
                for (auto& row : plane) row[0] = row[1] = constant_;
            return;
        }
        const std::size_t n = std::size_t((i.x() & 7) << 6 | (i.y() & 7) << 3 | (i.z() & 7));  // LeafNode::coordToOffset
        v[0][0][0] = data_[n], v[0][0][1] = data_[n + 1], v[0][1][0] = data_[n + 8], v[0][1][1] = data_[n + 9];
        v[1][0][0] = data_[n + 64], v[1][0][1] = data_[n + 65], v[1][1][0] = data_[n + 72], v[1][1][1] = data_[n + 73];
    }

    const Accessor* acc_;
    const openvdb::math::Transform* xf_;
    openvdb::Coord origin_{INT_MAX, INT_MAX, INT_MAX};  // no leaf origin: those are multiples of 8
    const float* data_ = nullptr;
    float constant_ = 0.0f;
};

}  // namespace weft
