#include "oracles/chebyshev_rings.hpp"

#include <tbb/parallel_for.h>

#include <atomic>
#include <bit>

namespace weft {

namespace {

// A box of bits, one row of 64-bit words per (y, z).
struct BitBox {
    int dx, dy, dz, words;
    std::vector<std::uint64_t> bits;
    BitBox(const openvdb::Coord& dim) : dx(dim.x()), dy(dim.y()), dz(dim.z()), words((dim.x() + 63) / 64) {
        bits.assign(std::size_t(words) * dy * dz, 0);
    }
    std::uint64_t* row(int y, int z) { return bits.data() + (std::size_t(z) * dy + y) * words; }
    const std::uint64_t* row(int y, int z) const { return bits.data() + (std::size_t(z) * dy + y) * words; }
};

// One ring along x and y within plane z: to = the plane's rows grown by one
// voxel along x (through `scratch`), then along y.
void growPlaneXY(const BitBox& from, BitBox& scratch, BitBox& to, int z) {
    const int w = from.words;
    for (int y = 0; y < from.dy; ++y) {
        const std::uint64_t* r = from.row(y, z);
        std::uint64_t* s = scratch.row(y, z);
        for (int i = 0; i < w; ++i) {
            const std::uint64_t left = (r[i] << 1) | (i > 0 ? r[i - 1] >> 63 : 0);
            const std::uint64_t right = (r[i] >> 1) | (i + 1 < w ? r[i + 1] << 63 : 0);
            s[i] = r[i] | left | right;
        }
    }
    for (int y = 0; y < from.dy; ++y) {
        std::uint64_t* t = to.row(y, z);
        const std::uint64_t* s = scratch.row(y, z);
        const std::uint64_t* below = y > 0 ? scratch.row(y - 1, z) : nullptr;
        const std::uint64_t* above = y + 1 < from.dy ? scratch.row(y + 1, z) : nullptr;
        for (int i = 0; i < w; ++i) t[i] = s[i] | (below ? below[i] : 0) | (above ? above[i] : 0);
    }
}

}  // namespace

std::optional<RingDistances> chebyshevRings(const openvdb::MaskTree& mask, int rings, std::size_t maxVoxels) {
    openvdb::CoordBBox box;
    if (rings < 0 || rings >= RingDistances::kBeyond || !mask.evalActiveVoxelBoundingBox(box)) return std::nullopt;
    box.expand(rings);  // growing `rings` times never leaves it
    const openvdb::Coord dim = box.dim();
    if (double(dim.x()) * dim.y() * dim.z() > double(maxVoxels)) return std::nullopt;
    RingDistances out{box, std::vector<std::uint8_t>(std::size_t(dim.x()) * dim.y() * dim.z(), RingDistances::kBeyond)};
    BitBox set(dim), scratch(dim), grown(dim);
    // The padding keeps every ring inside the box; the last word's bits past it stay clear all the same.
    const std::uint64_t lastWord = dim.x() % 64 ? (std::uint64_t(1) << (dim.x() % 64)) - 1 : ~std::uint64_t(0);
    for (auto leaf = mask.cbeginLeaf(); leaf; ++leaf)
        for (auto it = leaf->cbeginValueOn(); it; ++it) {
            const openvdb::Coord o = it.getCoord() - box.min();
            set.row(o.y(), o.z())[o.x() >> 6] |= std::uint64_t(1) << (o.x() & 63);
            out.ring[(std::size_t(o.z()) * dim.y() + o.y()) * dim.x() + o.x()] = 0;
        }
    for (int k = 1; k <= rings; ++k) {
        tbb::parallel_for(0, set.dz, [&](int z) { growPlaneXY(set, scratch, grown, z); });
        // Along z, and the voxels the ring added get distance k.
        std::atomic<bool> added{false};
        tbb::parallel_for(0, set.dz, [&](int z) {
            bool any = false;
            for (int y = 0; y < set.dy; ++y) {
                std::uint64_t* r = set.row(y, z);
                const std::uint64_t* g = grown.row(y, z);
                const std::uint64_t* front = z > 0 ? grown.row(y, z - 1) : nullptr;
                const std::uint64_t* back = z + 1 < set.dz ? grown.row(y, z + 1) : nullptr;
                std::uint8_t* ring = out.ring.data() + (std::size_t(z) * dim.y() + y) * dim.x();
                for (int i = 0; i < set.words; ++i) {
                    const std::uint64_t next = (g[i] | (front ? front[i] : 0) | (back ? back[i] : 0)) & (i + 1 < set.words ? ~std::uint64_t(0) : lastWord);
                    for (std::uint64_t fresh = next & ~r[i]; fresh; fresh &= fresh - 1) ring[i * 64 + std::countr_zero(fresh)] = std::uint8_t(k);
                    any = any || next != r[i];
                    r[i] = next;
                }
            }
            if (any) added.store(true, std::memory_order_relaxed);
        });
        if (!added) break;
    }
    return out;
}

}  // namespace weft
