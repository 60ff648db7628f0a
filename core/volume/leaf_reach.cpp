#include "core/volume/leaf_reach.hpp"

#include <openvdb/tree/ValueAccessor.h>

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>

#include "core/volume/topology_dilation.hpp"

namespace weft {

LeafDistances::LeafDistances(int reach)
    : K_(reach), B_(8 + 2 * reach), inBlock_(B_ >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << B_) - 1), rows_(std::size_t(B_) * B_), grown_(rows_.size()) {
    if (reach < 0 || reach > kMaxLeafReach) throw std::invalid_argument("LeafDistances: reach " + std::to_string(reach) + " outside [0, 16]");
}

const std::uint8_t* LeafDistances::of(const openvdb::MaskTree& mask, const openvdb::Coord& origin) {
    if (!load(mask, origin - openvdb::Coord(K_))) return nullptr;
    std::fill(std::begin(out_), std::end(out_), std::uint8_t(K_ + 1));
    std::fill(std::begin(done_), std::end(done_), 0);
    int left = 512 - record(0);
    for (int k = 1; k <= K_ && left > 0; ++k) grow(k), left -= record(k);
    return left == 512 ? nullptr : out_;
}

// The mask's leaves overlapping the block, a word (x) of each leaf at a
// time: its byte y holds the voxels along z. False when none has a voxel there.
bool LeafDistances::load(const openvdb::MaskTree& mask, const openvdb::Coord& lo) {
    std::fill(rows_.begin(), rows_.end(), 0);
    bool any = false;
    const openvdb::Coord hi = lo + openvdb::Coord(B_ - 1);
    for (int lx = lo.x() & ~7; lx <= hi.x(); lx += 8)
        for (int ly = lo.y() & ~7; ly <= hi.y(); ly += 8)
            for (int lz = lo.z() & ~7; lz <= hi.z(); lz += 8) {
                const auto* leaf = mask.probeConstLeaf(openvdb::Coord(lx, ly, lz));
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

// Growth step k: one voxel more in every direction, along z in each word,
// then y, then x. Only what the remaining K - k steps can carry into the
// leaf is kept up to date: step k writes rows k .. B - k - 1 in x and y,
// reading the ring around them that step k - 1 wrote.
void LeafDistances::grow(int k) {
    const int lo = k - 1, hi = B_ - k + 1;  // the rows step k - 1 left current
    for (int x = lo; x < hi; ++x)
        for (int y = lo; y < hi; ++y) {
            std::uint64_t& r = row(x, y);
            r = (r | r << 1 | r >> 1) & inBlock_;
        }
    for (int x = lo; x < hi; ++x)
        for (int y = lo + 1; y < hi - 1; ++y) grown_[std::size_t(x) * B_ + y] = row(x, y) | row(x, y - 1) | row(x, y + 1);
    for (int x = lo + 1; x < hi - 1; ++x)
        for (int y = lo + 1; y < hi - 1; ++y)
            row(x, y) = grown_[std::size_t(x) * B_ + y] | grown_[std::size_t(x - 1) * B_ + y] | grown_[std::size_t(x + 1) * B_ + y];
}

// Gives distance k to the leaf's voxels first set now; returns how many.
int LeafDistances::record(int k) {
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

// A leaf's neighbours within `reach` voxels are the leaves up to
// ceil(reach / 8) leaves away on each axis: the mask's leaves, as voxels of
// a tree of leaf indices (origin / 8), grown that many times by OpenVDB's
// 26-neighbour dilation. A list of every leaf's neighbours, sorted and made
// unique, held 27 entries per leaf and took one thread tens of milliseconds.
std::vector<openvdb::Coord> leafOriginsNear(const openvdb::MaskTree& mask, int reach) {
    openvdb::MaskTree leaves(false);
    {
        openvdb::tree::ValueAccessor<openvdb::MaskTree> acc(leaves);
        for (auto leaf = mask.cbeginLeaf(); leaf; ++leaf) {
            const openvdb::Coord& o = leaf->origin();  // a multiple of 8: exact division
            acc.setValueOn(openvdb::Coord(o.x() / 8, o.y() / 8, o.z() / 8));
        }
    }
    if (const int steps = (std::max(reach, 0) + 7) / 8)
        dilateTopology(leaves, steps, openvdb::tools::NN_FACE_EDGE_VERTEX, openvdb::tools::IGNORE_TILES);
    leaves.voxelizeActiveTiles();
    std::vector<openvdb::Coord> origins;
    origins.reserve(std::size_t(leaves.activeVoxelCount()));
    for (auto v = leaves.cbeginValueOn(); v; ++v) {
        const openvdb::Coord c = v.getCoord();
        origins.emplace_back(c.x() * 8, c.y() * 8, c.z() * 8);
    }
    std::sort(origins.begin(), origins.end());
    return origins;
}

}  // namespace weft
