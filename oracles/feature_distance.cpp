#include "oracles/feature_distance.hpp"

#include <openvdb/tools/Morphology.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

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

// How many rings the field holds: ring k gets its own distance only while
// ring k-1's is below the cap, and rings past the volume's extent hold no
// lookup (those read the cap), so the growth stops there too: a cap of
// thousands of voxels over a small grid would otherwise grow the field for
// minutes into gigabytes.
int ringCount(const OracleContext& ctx, float cap) {
    const openvdb::Coord extent = ctx.volume.indexBox().dim();
    const int rings = std::max({extent.x(), extent.y(), extent.z()}) + 2;
    int k = 0;
    while (k < rings && ringDistance(k, ctx, cap) < cap) ++k;
    return k;
}

float fieldCap(const OracleContext& ctx) {
    return std::max(float(ctx.sliceSpacing), float(ctx.sliceSpacing * double(1 << ctx.lmax)));
}

OracleField fieldOf(openvdb::FloatGrid::Ptr distance, float cap) {
    OracleField field;
    field.constant = cap;
    field.distance = std::move(distance);
    return field;
}

// Chebyshev distances (capped at K + 1) from the features to the voxels of
// the leaf at `origin`, from the features K voxels beyond the leaf on every
// side as a block of bits: each (x, y) of the block one 64-bit word of its
// voxels along z. Growing the block by one voxel in x, y and z (a 3^3 cube)
// is a few shifts and ORs per word; a leaf voxel first set after k growths
// is k voxels from the nearest feature.
class LeafDistances {
public:
    explicit LeafDistances(int K)
        : K_(K), B_(8 + 2 * K), inBlock_(B_ >= 64 ? ~0ull : (1ull << B_) - 1), rows_(std::size_t(B_) * B_), grown_(rows_.size()) {}

    // Distances of the leaf's 512 voxels, in the leaf's offset order (x
    // major); null when no feature is within K of the leaf.
    const std::uint8_t* of(const openvdb::MaskTree& features, const openvdb::Coord& origin) {
        if (!load(features, origin - openvdb::Coord(K_))) return nullptr;
        std::fill(std::begin(out_), std::end(out_), std::uint8_t(K_ + 1));
        std::fill(std::begin(done_), std::end(done_), 0);
        int left = 512 - record(0);
        for (int k = 1; k <= K_ && left > 0; ++k) grow(), left -= record(k);
        return left == 512 ? nullptr : out_;
    }

private:
    std::uint64_t& row(int x, int y) { return rows_[std::size_t(x) * B_ + y]; }

    // The mask's leaves overlapping the block, a word (x) of each leaf at a
    // time: its byte y holds the voxels along z. False when none has a voxel there.
    bool load(const openvdb::MaskTree& features, const openvdb::Coord& lo) {
        std::fill(rows_.begin(), rows_.end(), 0);
        bool any = false;
        const openvdb::Coord hi = lo + openvdb::Coord(B_ - 1);
        for (int lx = lo.x() & ~7; lx <= hi.x(); lx += 8)
            for (int ly = lo.y() & ~7; ly <= hi.y(); ly += 8)
                for (int lz = lo.z() & ~7; lz <= hi.z(); lz += 8) {
                    const auto* leaf = features.probeConstLeaf(openvdb::Coord(lx, ly, lz));
                    if (!leaf) continue;
                    const int shift = lz - lo.z();  // of the leaf's z = 0 in the block, -7 .. B - 1
                    for (int i = 0; i < 8; ++i) {
                        const int bx = lx + i - lo.x();
                        const std::uint64_t word = leaf->getValueMask().template getWord<std::uint64_t>(openvdb::Index(i));
                        if (bx < 0 || bx >= B_ || !word) continue;
                        for (int j = 0; j < 8; ++j) {
                            const int by = ly + j - lo.y();
                            const std::uint64_t z = (word >> (8 * j)) & 0xff;
                            if (by < 0 || by >= B_ || !z) continue;
                            const std::uint64_t bits = (shift >= 0 ? z << shift : z >> -shift) & inBlock_;
                            row(bx, by) |= bits;
                            any |= bits != 0;
                        }
                    }
                }
        return any;
    }

    // One voxel more in every direction: along z in each word, then y, then x.
    void grow() {
        for (std::uint64_t& r : rows_) r = (r | r << 1 | r >> 1) & inBlock_;
        for (int x = 0; x < B_; ++x)
            for (int y = 0; y < B_; ++y)
                grown_[std::size_t(x) * B_ + y] = row(x, y) | (y > 0 ? row(x, y - 1) : 0) | (y + 1 < B_ ? row(x, y + 1) : 0);
        for (int x = 0; x < B_; ++x)
            for (int y = 0; y < B_; ++y)
                row(x, y) = grown_[std::size_t(x) * B_ + y] | (x > 0 ? grown_[std::size_t(x - 1) * B_ + y] : 0) |
                            (x + 1 < B_ ? grown_[std::size_t(x + 1) * B_ + y] : 0);
    }

    // Gives distance k to the leaf's voxels first set now; returns how many.
    int record(int k) {
        int count = 0;
        for (int x = 0; x < 8; ++x)
            for (int y = 0; y < 8; ++y) {
                std::uint8_t& done = done_[x * 8 + y];
                std::uint8_t fresh = std::uint8_t((row(x + K_, y + K_) >> K_) & 0xff) & std::uint8_t(~done);
                done |= fresh;
                for (; fresh; fresh &= std::uint8_t(fresh - 1), ++count) out_[(x << 6) | (y << 3) | __builtin_ctz(fresh)] = std::uint8_t(k);
            }
        return count;
    }

    int K_, B_;
    std::uint64_t inBlock_;
    std::vector<std::uint64_t> rows_, grown_;
    std::uint8_t done_[64];
    std::uint8_t out_[512];
};

}  // namespace

OracleField distanceFieldByRings(const openvdb::MaskGrid& features, const OracleContext& ctx) {
    using namespace openvdb;
    const float minimum = float(ctx.sliceSpacing), cap = fieldCap(ctx);
    FloatGrid::Ptr distance = FloatGrid::create(cap);
    distance->setTransform(features.transform().copy());
    distance->setTree(std::make_shared<FloatTree>(features.tree(), cap, minimum, TopologyCopy()));
    distance->tree().voxelizeActiveTiles();
    // Ring k (Chebyshev distance exactly k) is the last ring grown by one
    // voxel (26-neighbourhood) less every voxel already given a distance, so
    // each step dilates a one-voxel shell, not the whole field.
    MaskTree ring(features.tree());
    ring.voxelizeActiveTiles();
    const int rings = ringCount(ctx, cap);
    for (int k = 1; k <= rings; ++k) {
        tools::dilateActiveValues(ring, 1, tools::NN_FACE_EDGE_VERTEX, tools::EXPAND_TILES);
        ring.topologyDifference(distance->tree());
        tools::pruneInactive(ring);
        ring.voxelizeActiveTiles();
        if (ring.empty()) break;
        distance->tree().topologyUnion(ring);  // new voxels hold the background (the cap) until set below
        const float value = ringDistance(k, ctx, cap);
        tree::LeafManager<MaskTree> leaves(ring);
        leaves.foreach([&](MaskTree::LeafNodeType& leaf, std::size_t) {
            FloatTree::LeafNodeType* target = distance->tree().probeLeaf(leaf.origin());
            for (auto it = leaf.cbeginValueOn(); it; ++it) target->setValueOnly(it.pos(), value);
        });
    }
    return fieldOf(distance, cap);
}

OracleField distanceFieldByBlocks(const openvdb::MaskGrid& features, const OracleContext& ctx) {
    using namespace openvdb;
    const float cap = fieldCap(ctx);
    const int K = ringCount(ctx, cap);
    if (K > kBlockRings) throw std::invalid_argument("distanceFieldByBlocks: " + std::to_string(K) + " rings, at most " + std::to_string(kBlockRings));
    MaskTree mask(features.tree());
    mask.voxelizeActiveTiles();
    // Every leaf within K voxels of a feature leaf.
    std::vector<Coord> origins;
    for (auto leaf = mask.cbeginLeaf(); leaf; ++leaf) {
        const Coord lo = leaf->origin() - Coord(K), hi = leaf->origin() + Coord(7 + K);
        for (int x = lo.x() & ~7; x <= hi.x(); x += 8)
            for (int y = lo.y() & ~7; y <= hi.y(); y += 8)
                for (int z = lo.z() & ~7; z <= hi.z(); z += 8) origins.emplace_back(x, y, z);
    }
    std::sort(origins.begin(), origins.end());
    origins.erase(std::unique(origins.begin(), origins.end()), origins.end());
    float value[256];
    for (int k = 0; k <= K; ++k) value[k] = ringDistance(k, ctx, cap);
    std::vector<std::unique_ptr<FloatTree::LeafNodeType>> leaves(origins.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, origins.size(), 16), [&](const tbb::blocked_range<std::size_t>& r) {
        LeafDistances distances(K);
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const std::uint8_t* d = distances.of(mask, origins[i]);
            if (!d) continue;
            auto leaf = std::make_unique<FloatTree::LeafNodeType>(origins[i], cap, false);
            for (Index n = 0; n < FloatTree::LeafNodeType::SIZE; ++n)
                if (d[n] <= K) leaf->setValueOn(n, value[d[n]]);
            leaves[i] = std::move(leaf);
        }
    });
    FloatGrid::Ptr distance = FloatGrid::create(cap);
    distance->setTransform(features.transform().copy());
    for (auto& leaf : leaves)
        if (leaf) distance->tree().addLeaf(leaf.release());
    return fieldOf(distance, cap);
}

// The distance field of a mask (distanceToFeatures without emission): by
// blocks where the rings are few (each leaf on its own, in parallel), else
// ring by ring.
OracleField distanceField(const openvdb::MaskGrid& features, const OracleContext& ctx) {
    if (ringCount(ctx, fieldCap(ctx)) <= kBlockRings) return distanceFieldByBlocks(features, ctx);
    return distanceFieldByRings(features, ctx);
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
    if (!ctx.volume.emission) return distanceField(features, ctx);
    openvdb::MaskGrid::Ptr merged = features.deepCopy();
    merged->tree().topologyUnion(emissionFeatures(ctx)->tree());
    return distanceField(*merged, ctx);
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
