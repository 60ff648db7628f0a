#include "core/volume/grid/leaf_reach.hpp"

#include <openvdb/tree/ValueAccessor.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <string>

#include "core/volume/grid/topology_dilation.hpp"

namespace weft {

LeafDistances::LeafDistances(int reach)
    : K_(reach), B_(8 + 2 * reach), S_(columnLeaves(reach)), P_(std::bit_width(unsigned(reach + 1))) {
    if (reach < 0 || reach > kMaxLeafReach) throw std::invalid_argument("LeafDistances: reach " + std::to_string(reach) + " outside [0, 16]");
    const int bits = 8 * S_ + 2 * K_;
    inBlock_ = bits >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << bits) - 1;
    rows_.resize(std::size_t(B_) * B_), grown_.resize(rows_.size());
    planes_.resize(64 * std::size_t(P_)), reached_.resize(64);
    within_.resize(8 * std::size_t(S_)), out_.resize(512 * std::size_t(S_)), found_.resize(std::size_t(S_));
}

void LeafDistances::column(const openvdb::MaskTree& mask, const openvdb::Coord& origin, int count) {
    if (count < 1 || count > S_) throw std::invalid_argument("LeafDistances: a column of " + std::to_string(count) + " leaves, at most " + std::to_string(S_));
    n_ = count;
    std::fill(found_.begin(), found_.end(), 0);
    if (!load(mask, origin - openvdb::Coord(K_), 8 * n_ + 2 * K_)) return;
    std::fill(planes_.begin(), planes_.end(), 0);
    bool all = record();
    for (int k = 1; k <= K_ && !all; ++k) grow(k), all = record();
    finish();
}

// The mask's leaves overlapping the block (B x B words, `depth` bits of
// each along z), a word (x) of each leaf at a time: its byte y holds the
// voxels along z. False when none has a voxel there. Bits past `depth`
// stay clear: what they miss is more than K voxels from the column's leaves.
bool LeafDistances::load(const openvdb::MaskTree& mask, const openvdb::Coord& lo, int depth) {
    std::fill(rows_.begin(), rows_.end(), 0);
    bool any = false;
    const openvdb::Coord hi = lo + openvdb::Coord(B_ - 1, B_ - 1, depth - 1);
    const std::uint64_t inDepth = depth >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << depth) - 1;
    for (int lx = lo.x() & ~7; lx <= hi.x(); lx += 8)
        for (int ly = lo.y() & ~7; ly <= hi.y(); ly += 8)
            for (int lz = lo.z() & ~7; lz <= hi.z(); lz += 8) {
                const auto* leaf = mask.probeConstLeaf(openvdb::Coord(lx, ly, lz));
                if (!leaf) continue;
                const int shift = lz - lo.z();  // of the leaf's z = 0 in the block, -7 .. depth - 1
                for (int i = 0; i < 8; ++i) {
                    const int bx = lx + i - lo.x();
                    const std::uint64_t word = leaf->getValueMask().template getWord<std::uint64_t>(openvdb::Index(i));
                    if (bx < 0 || bx >= B_ || !word) continue;
                    for (int j = 0; j < 8; ++j) {
                        const int by = ly + j - lo.y();
                        const std::uint64_t z = (word >> (8 * j)) & 0xff;
                        if (by < 0 || by >= B_ || !z) continue;
                        const std::uint64_t bits = (shift >= 0 ? z << shift : z >> -shift) & inDepth;
                        row(bx, by) |= bits;
                        any |= bits != 0;
                    }
                }
            }
    return any;
}

// Growth step k: one voxel more in every direction, along z in each word,
// then y, then x. Only what the remaining K - k steps can carry into the
// leaves is kept up to date: step k writes rows k .. B - k - 1 in x and y,
// reading the ring around them that step k - 1 wrote (along z the words'
// ends go stale the same way, never reaching the leaves).
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

namespace {

// Byte i of the result is bit i of `bits` (0 or 1).
std::uint64_t bytesOfBits(std::uint64_t bits) {
    const std::uint64_t picked = (bits * 0x0101010101010101ull) & 0x8040201008040201ull;  // byte i keeps bit i
    return ((picked + 0x7f7f7f7f7f7f7f7full) >> 7) & 0x0101010101010101ull;           // no byte carries into the next
}

}  // namespace

// Adds one to the count of every voxel of the column the last growth step
// did not reach (bit-sliced: a word's 8 n voxels at once), so a voxel
// first reached at step k counts k, and one never reached K + 1. True when
// every voxel is reached: later steps would add nothing.
bool LeafDistances::record() {
    const std::uint64_t leaves = n_ >= 8 ? ~std::uint64_t(0) : (std::uint64_t(1) << (8 * n_)) - 1;
    bool all = true;
    for (int xy = 0; xy < 64; ++xy) {
        const std::uint64_t bits = (row(K_ + xy / 8, K_ + xy % 8) >> K_) & leaves;
        reached_[std::size_t(xy)] = bits;
        all &= bits == leaves;
        std::uint64_t carry = ~bits & leaves;
        for (int p = 0; carry && p < P_; ++p) {
            std::uint64_t& plane = planes_[std::size_t(p) * 64 + std::size_t(xy)];
            const std::uint64_t next = plane & carry;
            plane ^= carry, carry = next;
        }
    }
    return all;
}

// The counts as bytes (a leaf's 8 voxels along z are 8 bytes of its
// offset order) and the voxels reached as value-mask words, per leaf.
void LeafDistances::finish() {
    for (int s = 0; s < n_; ++s) {
        std::uint8_t* out = out_.data() + 512 * std::size_t(s);
        std::uint64_t* within = within_.data() + 8 * std::size_t(s);
        int reached = 0;
        for (int x = 0; x < 8; ++x) {
            std::uint64_t word = 0;
            for (int y = 0; y < 8; ++y) {
                const std::size_t xy = std::size_t(8 * x + y);
                std::uint64_t d = 0;
                for (int p = 0; p < P_; ++p) d |= bytesOfBits((planes_[std::size_t(p) * 64 + xy] >> (8 * s)) & 0xff) << p;
                std::memcpy(out + 8 * xy, &d, 8);
                word |= ((reached_[xy] >> (8 * s)) & 0xff) << (8 * y);
            }
            within[x] = word;
            reached += __builtin_popcountll(word);
        }
        found_[std::size_t(s)] = std::uint16_t(reached);
    }
}

std::vector<std::size_t> columnRuns(const std::vector<openvdb::Coord>& origins, int leaves) {
    std::vector<std::size_t> runs;
    for (std::size_t i = 0; i < origins.size(); ++i) {
        const openvdb::Coord& a = origins[runs.empty() ? 0 : runs.back()];
        const openvdb::Coord& b = origins[i];
        if (runs.empty() || a.x() != b.x() || a.y() != b.y() || b.z() - a.z() >= 8 * leaves) runs.push_back(i);
    }
    runs.push_back(origins.size());
    return runs;
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
