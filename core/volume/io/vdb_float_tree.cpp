#include "core/volume/io/vdb_float_tree.hpp"

#include <array>
#include <bit>
#include <map>
#include <utility>
#include <vector>

namespace weft::vdbwalk {

namespace {

constexpr std::uint32_t kZip = 0x1, kActiveMask = 0x2, kBlosc = 0x4;  // io::COMPRESS_*
constexpr std::uint32_t kInternalNodeCompression = 214, kNodeMaskCompression = 222;
// io::readCompressedValues' per-node flag: what precedes the values.
constexpr std::int8_t kNoMaskOneInactive = 2, kMaskNoInactive = 3, kMaskOneInactive = 4, kMaskTwoInactive = 5,
                      kAllValues = 6;

using Words = std::vector<std::uint64_t>;
using LeafMask = std::array<std::uint64_t, 8>;  // 8^3 voxels
using Origin = std::array<std::int32_t, 3>;

std::uint64_t countOn(const std::uint64_t* words, std::size_t n) {
    std::uint64_t on = 0;
    for (std::size_t i = 0; i < n; ++i) on += std::uint64_t(std::popcount(words[i]));
    return on;
}

class FloatTreeWalk {
public:
    FloatTreeWalk(Walker& w, const FloatTreeFormat& f) : w_(w), f_(f) {}

    void run() {
        w_.skip(valueBytes(), "background value");
        const std::uint32_t tiles = w_.value<std::uint32_t>("root tile count");
        const std::uint32_t children = w_.value<std::uint32_t>("root child count");
        // A tile is a coordinate, a value and a flag, a child a coordinate
        // and at least its two 4096-byte node masks.
        const std::uint64_t end = f_.topologyEnd.value_or(w_.size());
        const std::uint64_t room = end > w_.pos() ? end - w_.pos() : 0;
        if (std::uint64_t(tiles) * (13 + valueBytes()) + std::uint64_t(children) * (12 + 8192) > room)
            w_.corrupt(std::to_string(tiles) + " root tiles and " + std::to_string(children) +
                       " children do not fit in the " + std::to_string(room) + " bytes of the grid's topology");
        // RootNode keeps its table in a map: a later entry at the same
        // coordinate replaces an earlier one, and the buffers follow the map's order.
        std::map<std::array<std::int32_t, 3>, std::size_t> table;
        std::vector<std::pair<std::size_t, std::size_t>> leavesOf{{0, 0}};  // entry 0: a tile
        for (std::uint32_t i = 0; i < tiles; ++i) {
            const auto origin = coordinate("root tile origin");
            w_.skip(valueBytes(), "root tile value");
            // Read into a bool: any byte but 0 or 1 is undefined behaviour.
            if (const auto active = w_.value<std::uint8_t>("root tile flag"); active > 1)
                w_.corrupt("root tile flag " + std::to_string(active) + " (not 0 or 1)");
            table[origin] = 0;
        }
        for (std::uint32_t i = 0; i < children; ++i) {
            const auto origin = coordinate("root child origin");
            const std::size_t first = leafMasks_.size();
            internalNode(5, f_.half, origin);
            table[origin] = leavesOf.size();
            leavesOf.emplace_back(first, leafMasks_.size());
        }
        if (f_.topologyEnd && w_.pos() != *f_.topologyEnd)
            w_.corrupt("the topology ends at byte " + std::to_string(w_.pos()) + ", not where the grid's buffers begin (" +
                       std::to_string(*f_.topologyEnd) + ")");
        for (const auto& [origin, entry] : table)
            for (std::size_t leaf = leavesOf[entry].first; leaf < leavesOf[entry].second; ++leaf) leafBuffer(leaf);
    }

private:
    // One value as it is held in memory (float or Vec3s), and as a chunk stores it.
    std::uint64_t valueBytes() const { return 4u * f_.components; }
    std::uint64_t storedBytes(bool half) const { return (half ? 2u : 4u) * f_.components; }

    // A root entry spans 4096^3 voxels from its origin; OpenVDB and weft add
    // to coordinates (node extents, bounding boxes), so an origin near the
    // int limits overflows. Real grids sit far inside +-2^30.
    std::array<std::int32_t, 3> coordinate(const char* what) {
        constexpr std::int32_t kReach = 1 << 30;
        std::array<std::int32_t, 3> c{};
        w_.bytes(c.data(), sizeof c, what);
        for (const std::int32_t x : c)
            if (x < -kReach || x > kReach)
                w_.corrupt(std::string(what) + " " + std::to_string(x) + " lies beyond the index range +-2^30 weft renders");
        return c;
    }

    // One io::readData: blosc or zip chunks state their size first; a
    // size <= 0 means that many uncompressed bytes follow.
    void chunk(std::uint64_t bytes, std::uint32_t compression) {
        if (!(compression & (kBlosc | kZip))) return w_.skip(bytes, "node values");
        const char* kind = (compression & kBlosc) ? "blosc" : "zip";
        const std::int64_t stated = w_.value<std::int64_t>("chunk size");
        if (stated <= 0) {
            const std::uint64_t raw = std::uint64_t(0) - std::uint64_t(stated);
            if (raw != bytes)
                w_.corrupt(std::string("uncompressed ") + kind + " chunk of " + std::to_string(raw) + " bytes where the node's values take " +
                           std::to_string(bytes));
            return w_.skip(raw, "uncompressed chunk");
        }
        if (compression & kBlosc) return w_.bloscBuffer(std::uint64_t(stated), bytes, "blosc chunk");
        w_.skip(std::uint64_t(stated), "zip chunk");
    }

    // io::readCompressedValues of `count` values of a node whose value mask is `mask`.
    void values(std::uint64_t count, const std::uint64_t* mask, std::size_t words, bool half) {
        std::int8_t flag = kAllValues;
        if (f_.version >= kNodeMaskCompression) flag = w_.value<std::int8_t>("node compression flag");
        if (flag == kNoMaskOneInactive || flag == kMaskOneInactive || flag == kMaskTwoInactive) w_.skip(valueBytes(), "inactive value");
        if (flag == kMaskTwoInactive) w_.skip(valueBytes(), "second inactive value");
        if (flag == kMaskNoInactive || flag == kMaskOneInactive || flag == kMaskTwoInactive) w_.skip(words * 8, "selection mask");
        if ((f_.compression & kActiveMask) && flag != kAllValues && f_.version >= kNodeMaskCompression)
            count = countOn(mask, words);
        if (half && count == 0) return;  // HalfReader reads nothing then
        chunk(count * storedBytes(half), f_.compression);
    }

    // InternalNode::readTopology of a node of 2^(3 log2Dim) entries; its
    // children are 16^3 nodes, theirs leaves. Child n of a node lies at
    // (n >> 2 log2Dim, n >> log2Dim, n) (each mod 2^log2Dim) child widths from its origin.
    void internalNode(int log2Dim, bool half, const Origin& origin) {
        const std::size_t entries = std::size_t(1) << (3 * log2Dim), words = entries / 64;
        Words childMask(words), valueMask(words);
        w_.bytes(childMask.data(), entries / 8, "internal node child mask");
        w_.bytes(valueMask.data(), entries / 8, "internal node value mask");
        const auto child = [&](bool childHalf, std::size_t n) {
            const std::int32_t width = log2Dim == 5 ? 128 : 8, last = (1 << log2Dim) - 1;
            const Origin at{origin[0] + width * std::int32_t(n >> (2 * log2Dim)), origin[1] + width * std::int32_t((n >> log2Dim) & last),
                            origin[2] + width * std::int32_t(n & last)};
            if (log2Dim == 5) return internalNode(4, childHalf, at);
            LeafMask m;
            w_.bytes(m.data(), sizeof m, "leaf value mask");
            leafMasks_.push_back(m);
            leafOrigins_.push_back(at);
        };
        if (f_.version < kInternalNodeCompression) {  // values stored between the children
            for (std::size_t i = 0; i < entries; ++i)
                if (childMask[i / 64] >> (i % 64) & 1) child(false, i);  // read without fromHalf then
                else w_.skip(valueBytes(), "internal node value");
            return;
        }
        const std::uint64_t count = f_.version < kNodeMaskCompression ? entries - countOn(childMask.data(), words) : entries;
        values(count, valueMask.data(), words, half);
        for (std::size_t i = 0; i < words; ++i)
            for (std::uint64_t bits = childMask[i]; bits; bits &= bits - 1) child(half, 64 * i + std::size_t(std::countr_zero(bits)));
    }

    // LeafNode::readBuffers: the value mask again, then the voxel values.
    void leafBuffer(std::size_t leaf) {
        if (f_.leaves) f_.leaves->push_back({leafOrigins_[leaf], w_.pos()});
        LeafMask m;
        w_.bytes(m.data(), sizeof m, "leaf buffer value mask");
        // OpenVDB takes the mask from either copy; valid files hold the same twice.
        if (m != leafMasks_[leaf]) w_.corrupt("a leaf's value mask in its buffer differs from the one in the topology");
        int buffers = 1;
        if (f_.version < kNodeMaskCompression) {
            w_.skip(12, "leaf origin");
            buffers = w_.value<std::int8_t>("leaf buffer count");
        }
        values(512, m.data(), m.size(), f_.half);
        for (int i = 1; i < buffers; ++i) chunk(512 * storedBytes(f_.half), f_.compression & kZip);  // older auxiliary buffers
    }

    Walker& w_;
    FloatTreeFormat f_;
    std::vector<LeafMask> leafMasks_;
    std::vector<Origin> leafOrigins_;
};

}  // namespace

void walkFloatTree(Walker& w, const FloatTreeFormat& format) { FloatTreeWalk(w, format).run(); }

}  // namespace weft::vdbwalk
