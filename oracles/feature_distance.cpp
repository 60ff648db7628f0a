#include "oracles/feature_distance.hpp"

#include "oracles/chebyshev_rings.hpp"

#include <openvdb/tools/Morphology.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

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

// How many rings a field grows: up to the cap, and no further than the
// volume's extent (rings past it hold no lookup, which reads the cap; a cap
// of thousands of voxels over a small grid would otherwise grow it for
// minutes into gigabytes).
int ringsToGrow(const OracleContext& ctx, float cap) {
    const openvdb::Coord extent = ctx.volume.indexBox().dim();
    const int limit = std::max({extent.x(), extent.y(), extent.z()}) + 2;
    int rings = 0;
    while (rings < limit && ringDistance(rings, ctx, cap) < cap) ++rings;
    return rings;
}

// The field from dense ring distances: a leaf wherever a voxel is within
// the rings, its voxels set in parallel.
void fillFromRings(openvdb::FloatTree& tree, const RingDistances& d, int rings, const OracleContext& ctx, float cap) {
    using namespace openvdb;
    const CoordBBox leafBox(d.box.min() & ~7, d.box.max() & ~7);
    std::vector<Coord> origins;
    for (int z = leafBox.min().z(); z <= leafBox.max().z(); z += 8)
        for (int y = leafBox.min().y(); y <= leafBox.max().y(); y += 8)
            for (int x = leafBox.min().x(); x <= leafBox.max().x(); x += 8) origins.emplace_back(x, y, z);
    std::vector<std::uint8_t> used(origins.size(), 0);
    auto leafVoxels = [&](std::size_t i) {
        CoordBBox b(origins[i], origins[i] + Coord(7));
        b.intersect(d.box);
        return b;
    };
    tbb::parallel_for(std::size_t(0), origins.size(), [&](std::size_t i) {
        for (auto c = leafVoxels(i).begin(); c; ++c)
            if (d.at(*c) <= rings) {
                used[i] = 1;
                return;
            }
    });
    for (std::size_t i = 0; i < origins.size(); ++i)
        if (used[i]) tree.touchLeaf(origins[i]);
    tbb::parallel_for(std::size_t(0), origins.size(), [&](std::size_t i) {
        if (!used[i]) return;
        FloatTree::LeafNodeType* leaf = tree.probeLeaf(origins[i]);
        for (auto c = leafVoxels(i).begin(); c; ++c)
            if (const int r = d.at(*c); r <= rings) leaf->setValueOn(*c, ringDistance(r, ctx, cap));
    });
}

// The same field grown ring by ring in the sparse tree: ring k (Chebyshev
// distance exactly k) is the last ring grown by one voxel (26-neighbourhood)
// less every voxel already given a distance.
void growRingsSparse(openvdb::FloatTree& tree, const openvdb::MaskTree& features, int rings, const OracleContext& ctx, float cap) {
    using namespace openvdb;
    MaskTree ring(features);
    for (int k = 1; k <= rings; ++k) {
        tools::dilateActiveValues(ring, 1, tools::NN_FACE_EDGE_VERTEX, tools::EXPAND_TILES);
        ring.topologyDifference(tree);
        tools::pruneInactive(ring);
        ring.voxelizeActiveTiles();
        if (ring.empty()) break;
        tree.topologyUnion(ring);  // new voxels hold the background (the cap) until set below
        const float value = ringDistance(k, ctx, cap);
        tree::LeafManager<MaskTree> leaves(ring);
        leaves.foreach([&](MaskTree::LeafNodeType& leaf, std::size_t) {
            FloatTree::LeafNodeType* target = tree.probeLeaf(leaf.origin());
            for (auto it = leaf.cbeginValueOn(); it; ++it) target->setValueOnly(it.pos(), value);
        });
    }
}

OracleField distanceField(const openvdb::MaskGrid& features, const OracleContext& ctx, std::size_t maxDenseVoxels) {
    using namespace openvdb;
    const float minimum = float(ctx.sliceSpacing);
    const float cap = std::max(minimum, float(ctx.sliceSpacing * double(1 << ctx.lmax)));
    FloatGrid::Ptr distance = FloatGrid::create(cap);
    distance->setTransform(features.transform().copy());
    MaskTree voxels(features.tree());
    voxels.voxelizeActiveTiles();
    distance->setTree(std::make_shared<FloatTree>(voxels, cap, minimum, TopologyCopy()));
    const int rings = ringsToGrow(ctx, cap);
    if (const auto dense = chebyshevRings(voxels, rings, maxDenseVoxels)) fillFromRings(distance->tree(), *dense, rings, ctx, cap);
    else growRingsSparse(distance->tree(), voxels, rings, ctx, cap);
    OracleField field;
    field.constant = cap;
    field.distance = distance;
    return field;
}

openvdb::MaskGrid::Ptr emissionFeatures(const OracleContext& ctx) {
    using namespace openvdb;
    const Vec3SGrid& emission = *ctx.volume.emission;
    MaskGrid::Ptr mask = MaskGrid::create(false);
    mask->setTransform(emission.transform().copy());
    mask->tree().topologyUnion(emission.tree());
    mask->tree().voxelizeActiveTiles();
    tools::dilateActiveValues(mask->tree(), 1, tools::NN_FACE, tools::EXPAND_TILES);  // the edges of the glow
    const double threshold2 = ctx.epsilon * ctx.epsilon;
    tree::LeafManager<MaskTree> leaves(mask->tree());
    leaves.foreach([&](MaskTree::LeafNodeType& leaf, std::size_t) {
        Vec3SGrid::ConstAccessor acc = emission.getConstAccessor();
        for (auto it = leaf.beginValueOn(); it; ++it) {
            double g2 = 0;
            for (int axis = 0; axis < 3; ++axis) {
                Coord lo = it.getCoord(), hi = lo;
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

OracleField distanceToFeatures(const openvdb::MaskGrid& features, const OracleContext& ctx) {
    if (!ctx.volume.emission) return distanceField(features, ctx, kMaxDenseRingVoxels);
    openvdb::MaskGrid::Ptr merged = features.deepCopy();
    merged->tree().topologyUnion(emissionFeatures(ctx)->tree());
    return distanceField(*merged, ctx, kMaxDenseRingVoxels);
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
                                    const openvdb::math::Transform& transform) {
    openvdb::MaskGrid::Ptr mask = openvdb::MaskGrid::create(false);
    mask->setTransform(transform.copy());
    for (std::size_t i = 0; i < bricks.size(); ++i)
        if (isFeature[i]) mask->tree().fill(bricks[i].box, true, true);
    mask->tree().voxelizeActiveTiles();
    return mask;
}

}  // namespace weft
