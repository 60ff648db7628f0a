#include "oracles/feature_distance.hpp"

#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/volume/grid/octant_shift.hpp"
#include "core/volume/grid/topology_dilation.hpp"

namespace weft {

double sliceOpacity(const Volume& volume, double spacing, float value) {
    return -std::expm1(-double(volume.tf.lookup(value).extinction) * spacing);
}

namespace {

// Distance stored for voxels at Chebyshev distance k from a feature: k
// itself, the paper's "distance to the nearest feature voxel" (Chebyshev
// never exceeds Euclidean, so it errs on the dense side).
float ringDistance(int k, const OracleContext& ctx, float cap) {
    return std::clamp(float(k), float(ctx.sliceSpacing), cap);
}

}  // namespace

// The largest channel of one slice's emitted radiance (e x spacing), the
// change in colour a slice can make, as a slice's opacity is for absorption.
double sliceEmission(const openvdb::Vec3s& e, double spacing) {
    return double(std::max({e[0], e[1], e[2]})) * spacing;
}

namespace {

// How many rings the field holds beyond the features (ring 0): ring k is
// stored only while its distance is below the cap (farther voxels read the
// cap as the grid's background), and rings past the volume's extent hold
// no lookup (those read the cap), so the growth stops there too: a cap of
// thousands of voxels over a small grid would otherwise grow the field for
// minutes into gigabytes.
int ringCount(const OracleContext& ctx, float cap) {
    const openvdb::Coord extent = ctx.volume.indexBox().dim();
    const int rings = std::max({extent.x(), extent.y(), extent.z()}) + 2;
    int k = 0;
    while (k < rings && ringDistance(k + 1, ctx, cap) < cap) ++k;
    return k;
}

float fieldCap(const OracleContext& ctx) {
    return std::max(float(ctx.sliceSpacing), float(ctx.sliceSpacing * double(1 << ctx.lmax)));
}

// A field of `rings` whose index k (at most `stored`) holds ring k's distance, the rest the cap.
OracleField fieldOf(std::shared_ptr<const RingTree> rings, int stored, const OracleContext& ctx, float cap) {
    OracleField field;
    field.constant = cap;
    field.rings = std::move(rings);
    field.distances.assign(256, cap);
    for (int k = 0; k <= stored; ++k) field.distances[k] = ringDistance(k, ctx, cap);
    return field;
}

// Rings beyond this share its index (and distance, which is never more than theirs).
constexpr int kLastRingIndex = kFarRing - 1;

}  // namespace

openvdb::Coord oracleShift(const Volume& volume) {
    // Room below the data for the candidates' one-voxel apron and every ring
    // grown by blocks; fields grown ring by ring may reach further (they stay
    // correct, only their trees cost more).
    constexpr int kRoom = 8 * ((kMaxLeafReach + 1 + 7) / 8);
    if (volume.activeBox.empty()) return openvdb::Coord(0);
    return openvdb::Coord(kRoom) - widthBelow(volume.activeBox, 8);
}

namespace {

template <class GridT>
openvdb::MaskGrid::Ptr activeAndFaceNeighboursOf(const GridT& grid, const openvdb::Coord& shift) {
    openvdb::MaskGrid::Ptr mask = shiftedMask(grid.transform(), shift);
    addShiftedTopology(grid.tree(), shift, mask->tree());
    mask->tree().voxelizeActiveTiles();
    dilateTopology(mask->tree(), 1, openvdb::tools::NN_FACE, openvdb::tools::EXPAND_TILES);
    return mask;
}

}  // namespace

openvdb::MaskGrid::Ptr activeAndFaceNeighbours(const openvdb::FloatGrid& grid, const openvdb::Coord& shift) {
    return activeAndFaceNeighboursOf(grid, shift);
}

openvdb::MaskGrid::Ptr activeAndFaceNeighbours(const openvdb::Vec3SGrid& grid, const openvdb::Coord& shift) {
    return activeAndFaceNeighboursOf(grid, shift);
}

OracleField distanceFieldByRings(const openvdb::MaskGrid& features, const OracleContext& ctx) {
    using namespace openvdb;
    const float cap = fieldCap(ctx);
    auto distance = std::make_shared<RingTree>(features.tree(), kFarRing, std::uint8_t(0), TopologyCopy());
    distance->voxelizeActiveTiles();
    // Ring k (Chebyshev distance exactly k) is the last ring grown by one
    // voxel (26-neighbourhood) less every voxel already given a distance, so
    // each step dilates a one-voxel shell, not the whole field.
    MaskTree ring(features.tree());
    ring.voxelizeActiveTiles();
    const int rings = ringCount(ctx, cap);
    for (int k = 1; k <= rings; ++k) {
        dilateTopology(ring, 1, tools::NN_FACE_EDGE_VERTEX, tools::EXPAND_TILES);
        ring.topologyDifference(*distance);
        tools::pruneInactive(ring);
        ring.voxelizeActiveTiles();
        if (ring.empty()) break;
        distance->topologyUnion(ring);  // new voxels hold the background (the cap) until set below
        const std::uint8_t index = std::uint8_t(std::min(k, kLastRingIndex));
        tree::LeafManager<MaskTree> leaves(ring);
        leaves.foreach([&](MaskTree::LeafNodeType& leaf, std::size_t) {
            RingTree::LeafNodeType* target = distance->probeLeaf(leaf.origin());
            for (auto it = leaf.cbeginValueOn(); it; ++it) target->setValueOnly(it.pos(), index);
        });
    }
    return fieldOf(std::move(distance), std::min(rings, kLastRingIndex), ctx, cap);
}

OracleField distanceFieldByBlocks(const openvdb::MaskGrid& features, const OracleContext& ctx) {
    using namespace openvdb;
    const float cap = fieldCap(ctx);
    const int K = ringCount(ctx, cap);
    if (K > kMaxLeafReach) throw std::invalid_argument("distanceFieldByBlocks: " + std::to_string(K) + " rings, at most " + std::to_string(kMaxLeafReach));
    MaskTree mask(features.tree());
    mask.voxelizeActiveTiles();
    auto distance = std::make_shared<RingTree>(kFarRing);
    // LeafDistances gives each voxel its ring (K + 1: farther, whose index
    // holds the cap as the background's does): the leaf's values as they
    // are, and its value mask on where the ring is at most K.
    addLeavesNear(*distance, mask, K, [&](const Coord& origin, const std::uint8_t* d, const std::uint64_t* within) {
        auto leaf = std::make_unique<RingTree::LeafNodeType>(origin, kFarRing, false);
        std::memcpy(leaf->buffer().data(), d, RingTree::LeafNodeType::SIZE);
        setValueMaskWords(*leaf, within);
        return leaf;
    });
    return fieldOf(std::move(distance), K, ctx, cap);
}

// The distance field of a mask (distanceToFeatures without emission): by
// blocks where the rings are few (each leaf on its own, in parallel), else
// ring by ring.
OracleField distanceField(const openvdb::MaskGrid& features, const OracleContext& ctx) {
    if (ringCount(ctx, fieldCap(ctx)) <= kMaxLeafReach) return distanceFieldByBlocks(features, ctx);
    return distanceFieldByRings(features, ctx);
}

openvdb::MaskGrid::Ptr emissionFeatures(const OracleContext& ctx, const openvdb::Coord& shift) {
    using namespace openvdb;
    const Vec3SGrid& emission = *ctx.volume.emission;
    MaskGrid::Ptr mask = activeAndFaceNeighbours(emission, shift);  // the glow and its edges
    const double threshold2 = ctx.epsilon * ctx.epsilon;
    tree::LeafManager<MaskTree> leaves(mask->tree());
    leaves.foreach([&](MaskTree::LeafNodeType& leaf, std::size_t) {
        Vec3SGrid::ConstAccessor acc = emission.getConstAccessor();
        for (auto it = leaf.beginValueOn(); it; ++it) {
            double g2 = 0;
            for (int axis = 0; axis < 3; ++axis) {
                Coord lo = it.getCoord() - shift, hi = lo;
                --lo[axis], ++hi[axis];
                const double g = 0.5 * (sliceEmission(acc.getValue(hi), ctx.sliceSpacing) - sliceEmission(acc.getValue(lo), ctx.sliceSpacing));
                g2 += g * g;
            }
            if (!(g2 > threshold2)) leaf.setValueOff(it.pos());
        }
    });
    tools::pruneInactive(mask->tree());
    return mask;
}

OracleField distanceToFeatures(const openvdb::MaskGrid& features, const OracleContext& ctx, const openvdb::Coord& shift) {
    OracleField field;
    if (!ctx.volume.emission) {
        field = distanceField(features, ctx);
    } else {
        openvdb::MaskGrid::Ptr merged = features.deepCopy();
        merged->tree().topologyUnion(emissionFeatures(ctx, shift)->tree());
        field = distanceField(*merged, ctx);
    }
    field.shift = shift;
    return field;
}

std::vector<BrickRange> brickRanges(const openvdb::FloatGrid& grid) {
    using namespace openvdb;
    std::vector<const FloatTree::LeafNodeType*> leaves;
    grid.tree().getNodes(leaves);
    std::vector<BrickRange> ranges(leaves.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        FloatGrid::ConstAccessor acc = grid.getConstAccessor();
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            CoordBBox box = leaves[i]->getNodeBoundingBox();
            box.expand(1);
            float lo = std::numeric_limits<float>::infinity(), hi = -lo;
            for (auto c = box.begin(); c; ++c) {
                const float v = acc.getValue(*c);
                lo = std::min(lo, v), hi = std::max(hi, v);
            }
            ranges[i] = {leaves[i]->getNodeBoundingBox(), lo, hi};
        }
    });
    for (auto it = grid.tree().cbeginValueOn(); it; ++it)
        if (!it.isVoxelValue()) ranges.push_back({it.getBoundingBox(), *it, *it});
    return ranges;
}

openvdb::MaskGrid::Ptr maskOfBricks(const std::vector<BrickRange>& bricks, const std::vector<bool>& isFeature,
                                    const openvdb::math::Transform& transform, const openvdb::Coord& shift) {
    openvdb::MaskGrid::Ptr mask = shiftedMask(transform, shift);
    for (std::size_t i = 0; i < bricks.size(); ++i)
        if (isFeature[i]) mask->tree().fill(openvdb::CoordBBox(bricks[i].box.min() + shift, bricks[i].box.max() + shift), true, true);
    mask->tree().voxelizeActiveTiles();
    return mask;
}

}  // namespace weft
