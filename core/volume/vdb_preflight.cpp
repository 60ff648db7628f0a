#include "core/volume/vdb_preflight.hpp"

#include <fstream>
#include <sstream>
#include <vector>

#include <openvdb/version.h>

#include "core/base/error.hpp"

namespace weft {

namespace {

constexpr std::int64_t kMagic = 0x56444220;  // " BDV"
// Format 213 (the root node map) predates OpenVDB's first public release;
// the newest is the one this OpenVDB writes.
constexpr std::uint32_t kOldestWalked = 213, kNewestWalked = openvdb::OPENVDB_FILE_VERSION;
constexpr std::uint32_t kMaxName = 1 << 20;  // names and type names: a megabyte is already absurd

// Bytes of the linear maps' data after their type name (OpenVDB's Map::read).
std::int64_t mapDataBytes(const std::string& type) {
    if (type == "AffineMap" || type == "UnitaryMap") return 16 * 8;                       // Mat4d
    if (type == "ScaleMap" || type == "UniformScaleMap") return 5 * 24;                   // five Vec3d
    if (type == "ScaleTranslateMap" || type == "UniformScaleTranslateMap") return 6 * 24;  // translation + the above
    if (type == "TranslationMap") return 24;
    return -1;  // a frustum or unknown map: the walk stops before the topology
}

class Walker {
public:
    Walker(std::istream& in, std::uint64_t size, std::string name) : in_(in), size_(size), name_(std::move(name)) {}

    [[noreturn]] void corrupt(const std::string& what) const {
        throw Error("volume '" + name_ + "': corrupt file (" + what + " at byte " + std::to_string(pos_) + ")");
    }
    std::uint64_t left() const { return size_ - pos_; }
    std::uint64_t pos() const { return pos_; }

    void bytes(void* out, std::uint64_t n, const char* what) {
        if (n > left()) corrupt(std::string(what) + " runs past the end of the file");
        in_.read(static_cast<char*>(out), std::streamsize(n));
        if (!in_) corrupt(std::string(what) + " cannot be read");
        pos_ += n;
    }
    template <typename T> T value(const char* what) {
        T v{};
        bytes(&v, sizeof v, what);
        return v;
    }
    void skip(std::uint64_t n, const char* what) {
        if (n > left()) corrupt(std::string(what) + " of " + std::to_string(n) + " bytes runs past the end of the file");
        in_.seekg(std::streamoff(n), std::ios::cur);
        pos_ += n;
    }
    void seek(std::int64_t at, const char* what) {
        if (at < 0 || std::uint64_t(at) > size_) corrupt(std::string(what) + " " + std::to_string(at) + " lies outside the file");
        in_.clear();
        in_.seekg(at);
        pos_ = std::uint64_t(at);
    }
    // OpenVDB's readString: a 32-bit length, then the characters.
    std::string text(const char* what, std::uint32_t maxLength = kMaxName) {
        const std::uint32_t n = value<std::uint32_t>(what);
        if (n > maxLength || n > left())
            corrupt(std::string(what) + " claims " + std::to_string(n) + " bytes");
        std::string s(n, '\0');
        bytes(s.data(), n, what);
        return s;
    }

private:
    std::istream& in_;
    std::uint64_t size_, pos_ = 0;
    std::string name_;
};

// MetaMap::readMeta: a count, then name, type name and sized value each.
void walkMetadata(Walker& w, const char* where) {
    const std::int32_t count = w.value<std::int32_t>(where);
    // Each entry holds at least its three 32-bit lengths.
    if (count < 0 || std::uint64_t(count) * 12 > w.left()) w.corrupt(std::string(where) + " count " + std::to_string(count));
    for (std::int32_t i = 0; i < count; ++i) {
        w.text("metadata name");
        w.text("metadata type name");
        const std::uint32_t n = w.value<std::uint32_t>("metadata value size");
        w.skip(n, "metadata value");
    }
}

struct Descriptor {
    std::int64_t gridPos, blockPos, endPos;
    bool instance;
    bool standardFloatTree;  // Tree_float_5_4_3: root records of a known size
};

// A grid's compression flags, metadata, transform and root counts (File::readGrid's order).
void walkGrid(Walker& w, const Descriptor& d, std::uint32_t version) {
    w.seek(d.gridPos, "grid position");
    if (version >= 222) w.value<std::uint32_t>("grid compression");
    walkMetadata(w, "grid metadata");
    const std::string map = w.text("transform type");
    const std::int64_t mapBytes = mapDataBytes(map);
    if (version < 219 || mapBytes < 0 || d.instance || !d.standardFloatTree) return;  // older transforms, other layouts
    w.skip(std::uint64_t(mapBytes), "transform data");
    w.value<std::int32_t>("tree buffer count");
    // RootNode::readTopology: background, tile and child counts; a tile is
    // a coordinate, a value and a flag (17 bytes with float values), a child
    // a coordinate and at least its two 4096-byte node masks.
    w.value<float>("background value");
    const std::uint32_t tiles = w.value<std::uint32_t>("root tile count");
    const std::uint32_t children = w.value<std::uint32_t>("root child count");
    const std::uint64_t room = d.blockPos > std::int64_t(w.pos()) ? std::uint64_t(d.blockPos) - w.pos() : 0;
    if (std::uint64_t(tiles) * 17 + std::uint64_t(children) * (12 + 8192) > room)
        w.corrupt(std::to_string(tiles) + " root tiles and " + std::to_string(children) + " children do not fit in the " +
                  std::to_string(room) + " bytes of the grid's topology");
}

void walk(std::istream& in, std::uint64_t size, const std::string& name) {
    Walker w(in, size, name);
    if (size < 8 || w.value<std::int64_t>("magic number") != kMagic) return;  // not a VDB: OpenVDB says so
    const std::uint32_t version = w.value<std::uint32_t>("file version");
    // Outside these versions OpenVDB reads lengths this walk cannot check
    // (a 40-byte header of version 0 made it allocate 1.7 GB), so the file is
    // refused rather than trusted.
    if (version < kOldestWalked || version > kNewestWalked)
        throw Error("volume '" + name + "': OpenVDB file format version " + std::to_string(version) +
                    " is not one weft reads (" + std::to_string(kOldestWalked) + " to " + std::to_string(kNewestWalked) +
                    "); re-save the file with a current OpenVDB");
    w.value<std::uint32_t>("library major version");
    w.value<std::uint32_t>("library minor version");
    const bool offsets = w.value<std::uint8_t>("grid offsets flag") != 0;
    if (version >= 218) w.skip(36, "file UUID");
    if (version >= 220 && version < 222) w.value<std::uint32_t>("file compression");
    walkMetadata(w, "file metadata");
    if (!offsets) return;
    const std::int32_t grids = w.value<std::int32_t>("grid count");
    if (grids < 0 || std::uint64_t(grids) * 32 > w.left()) w.corrupt("grid count " + std::to_string(grids));
    std::vector<Descriptor> descriptors;
    for (std::int32_t i = 0; i < grids; ++i) {
        w.text("grid name");
        const std::string type = w.text("grid type");
        const bool instance = version >= 216 && !w.text("grid instance parent").empty();
        Descriptor d{w.value<std::int64_t>("grid position"), w.value<std::int64_t>("grid data position"),
                     w.value<std::int64_t>("grid end position"), instance,
                     type == "Tree_float_5_4_3" || type == "Tree_float_5_4_3_HalfFloat"};
        const bool ordered = d.gridPos >= 0 && d.gridPos <= d.blockPos && d.blockPos <= d.endPos;
        if (ordered && std::uint64_t(d.endPos) > size)
            throw Error("volume '" + name + "': the file is cut short (grid " + std::to_string(i + 1) + " ends at byte " +
                        std::to_string(d.endPos) + ", the file holds " + std::to_string(size) + ")");
        if (!ordered)
            w.corrupt("grid positions " + std::to_string(d.gridPos) + ", " + std::to_string(d.blockPos) + ", " +
                      std::to_string(d.endPos) + " of a " + std::to_string(size) + "-byte file");
        descriptors.push_back(d);
        w.seek(d.endPos, "next grid descriptor");
    }
    for (const Descriptor& d : descriptors) walkGrid(w, d, version);
}

}  // namespace

void preflightVdb(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) return;  // unreadable: the caller's open says so
    const std::streamoff size = in.tellg();
    in.seekg(0);
    walk(in, size > 0 ? std::uint64_t(size) : 0, path);
}

void preflightVdbBytes(const std::string& bytes, const std::string& name) {
    std::istringstream in(bytes);
    walk(in, bytes.size(), name);
}

}  // namespace weft
