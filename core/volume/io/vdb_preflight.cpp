#include "core/volume/io/vdb_preflight.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <limits>
#include <mutex>
#include <optional>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include <openvdb/Metadata.h>
#include <openvdb/version.h>

#include "core/base/error.hpp"
#include "core/base/files/mapped_file.hpp"
#include "core/volume/grid/vdb_init.hpp"
#include "core/volume/io/vdb_float_tree.hpp"
#include "core/volume/io/vdb_walker.hpp"

namespace weft {

namespace {

using vdbwalk::Walker;

constexpr std::int64_t kMagic = 0x56444220;  // " BDV"
// Format 220 (compression flags in the file) predates OpenVDB 1.0; older
// files store transforms this walk does not know, so their trees could not
// be checked. The newest is the one this OpenVDB writes.
constexpr std::uint32_t kOldestWalked = 220, kNewestWalked = openvdb::OPENVDB_FILE_VERSION;

// Bytes of the linear maps' data after their type name (OpenVDB's Map::read).
std::int64_t mapDataBytes(const std::string& type) {
    if (type == "AffineMap" || type == "UnitaryMap") return 16 * 8;                       // Mat4d
    if (type == "ScaleMap" || type == "UniformScaleMap") return 5 * 24;                   // five Vec3d
    if (type == "ScaleTranslateMap" || type == "UniformScaleTranslateMap") return 6 * 24;  // translation + the above
    if (type == "TranslationMap") return 24;
    return -1;  // a frustum or unknown map: the walk stops before the topology
}

// DelayedLoadMetadata::readValue (type "__delayedload", in most files):
// a count, then per leaf a mask byte and an 8-byte compressed size, each
// array blosc-compressed (a size > 0) or raw (0); sizes of UINT32_MAX mean
// no compressed sizes. What is left of its stated size is skipped.
void walkDelayedLoad(Walker& w, std::uint32_t stated) {
    if (stated == 0) return;
    const std::uint64_t start = w.pos();
    const std::uint32_t count = w.value<std::uint32_t>("delayed-load count");
    const auto array = [&](std::uint64_t itemBytes, bool optional) {
        const std::uint32_t bytes = w.value<std::uint32_t>("delayed-load array size");
        if (optional && bytes == std::numeric_limits<std::uint32_t>::max()) return;
        if (bytes > 0) w.bloscBuffer(bytes, count * itemBytes, "delayed-load array", /*padded=*/true);
        else w.skip(count * itemBytes, "delayed-load array");
    };
    array(1, false);
    array(8, true);
    const std::uint64_t used = w.pos() - start;
    if (used > stated)
        w.corrupt("delayed-load metadata of " + std::to_string(used) + " bytes where its size states " + std::to_string(stated));
    w.skip(stated - used, "delayed-load metadata");
}

// One metadata value. A registered type of fixed size (bool, int32, vec3d,
// mat4d...) is read at its own size whatever size the file states, so the
// two must agree or OpenVDB's reading and this walk part ways.
void walkMetaValue(Walker& w, const std::string& type, std::uint32_t stated) {
    if (type == "__delayedload") return walkDelayedLoad(w, stated);
    if (type != "string" && openvdb::Metadata::isRegisteredType(type)) {
        const std::uint32_t size = openvdb::Metadata::createMetadata(type)->size();
        if (stated != size)
            w.corrupt(type + " metadata stating " + std::to_string(stated) + " bytes where OpenVDB reads " + std::to_string(size));
        if (type == "bool") {  // read into a bool: any byte but 0 or 1 is undefined behaviour
            if (const auto b = w.value<std::uint8_t>("bool metadata"); b > 1)
                w.corrupt("bool metadata " + std::to_string(b) + " (not 0 or 1)");
            return;
        }
    }
    w.skip(stated, "metadata value");
}

// MetaMap::readMeta: a count, then name, type name and sized value each.
void walkMetadata(Walker& w, const char* where) {
    const std::int32_t count = w.value<std::int32_t>(where);
    // Each entry holds at least its three 32-bit lengths.
    if (count < 0 || std::uint64_t(count) * 12 > w.left()) w.corrupt(std::string(where) + " count " + std::to_string(count));
    for (std::int32_t i = 0; i < count; ++i) {
        w.text("metadata name");
        const std::string type = w.text("metadata type name");
        walkMetaValue(w, type, w.value<std::uint32_t>("metadata value size"));
    }
}

struct FileFormat {
    std::uint32_t version;
    std::uint32_t compression;  // before 222 the file's, later each grid's
    std::uint32_t libraryMajor = 0, libraryMinor = 0;
};

struct Descriptor {
    std::string name, type;
    std::int64_t gridPos = 0, blockPos = 0, endPos = 0;  // all 0 in a file written as a stream
    bool instance = false;
    // The layouts walkFloatTree knows: float and Vec3s values, full or half.
    bool floatTree() const { return components() > 0; }
    bool halfFloat() const { return type.ends_with("_HalfFloat"); }
    int components() const {
        if (type == "Tree_float_5_4_3" || type == "Tree_float_5_4_3_HalfFloat") return 1;
        if (type == "Tree_vec3s_5_4_3" || type == "Tree_vec3s_5_4_3_HalfFloat") return 3;
        return 0;
    }
};

// GridDescriptor::read: names, then the three positions.
Descriptor readDescriptor(Walker& w, const FileFormat& file) {
    Descriptor d;
    d.name = w.text("grid name");
    d.type = w.text("grid type");
    d.instance = file.version >= 216 && !w.text("grid instance parent").empty();
    d.gridPos = w.value<std::int64_t>("grid position");
    d.blockPos = w.value<std::int64_t>("grid data position");
    d.endPos = w.value<std::int64_t>("grid end position");
    return d;
}

// A grid's compression flags, metadata, transform and, for a float tree,
// every node and chunk (Archive::readGrid's order). False when the walk
// stopped before a tree it does not know (another value type, a frustum
// transform): readFloatGrid refuses such grids before OpenVDB reads them.
bool walkGrid(Walker& w, const Descriptor& d, const FileFormat& file, std::optional<std::uint64_t> topologyEnd, VdbLayout& layout) {
    const std::uint32_t compression = file.version >= 222 ? w.value<std::uint32_t>("grid compression") : file.compression;
    walkMetadata(w, "grid metadata");
    const std::int64_t mapBytes = mapDataBytes(w.text("transform type"));
    if (mapBytes < 0) return false;
    w.skip(std::uint64_t(mapBytes), "transform data");
    if (d.instance) return true;  // the parent's tree is walked where it lies
    if (!d.floatTree()) return false;
    w.value<std::int32_t>("tree buffer count");
    // Two grids stored under one name (not as OpenVDB writes them): which
    // one OpenVDB reads is its choice, so neither keeps a layout.
    const bool seen = layout.grids.count(d.name) > 0;
    VdbGridLayout& grid = layout.grids[d.name];
    grid = {file.version, file.libraryMajor, file.libraryMinor, compression, d.halfFloat(), {}, !seen, d.components()};
    vdbwalk::walkFloatTree(w, {file.version, compression, d.halfFloat(), d.components(), topologyEnd, &grid.leaves});
    if (seen) grid.leaves.clear();
    return true;
}

// A file with grid offsets: descriptors and grids interleaved, each grid
// walked at the position its descriptor states.
void walkIndexedGrids(Walker& w, const FileFormat& file, std::int32_t grids, VdbLayout& layout) {
    std::vector<Descriptor> descriptors;
    for (std::int32_t i = 0; i < grids; ++i) {
        const Descriptor d = readDescriptor(w, file);
        const bool ordered = d.gridPos >= 0 && d.gridPos <= d.blockPos && d.blockPos <= d.endPos;
        if (ordered && std::uint64_t(d.endPos) > w.size())
            throw Error("volume '" + w.name() + "': the file is cut short (grid " + std::to_string(i + 1) + " ends at byte " +
                        std::to_string(d.endPos) + ", the file holds " + std::to_string(w.size()) + ")");
        if (!ordered)
            w.corrupt("grid positions " + std::to_string(d.gridPos) + ", " + std::to_string(d.blockPos) + ", " +
                      std::to_string(d.endPos) + " of a " + std::to_string(w.size()) + "-byte file");
        descriptors.push_back(d);
        w.seek(d.endPos, "next grid descriptor");
    }
    for (const Descriptor& d : descriptors) {
        w.seek(d.gridPos, "grid position");
        if (walkGrid(w, d, file, std::uint64_t(d.blockPos), layout) && w.pos() > std::uint64_t(d.endPos))
            w.corrupt("the grid's buffers run past its end position " + std::to_string(d.endPos));
    }
}

// A file written as a stream has no offsets, and OpenVDB reads every grid
// in it to find one, so every grid must be walked.
void walkStreamedGrids(Walker& w, const FileFormat& file, std::int32_t grids, VdbLayout& layout) {
    for (std::int32_t i = 0; i < grids; ++i) {
        const Descriptor d = readDescriptor(w, file);
        if (!walkGrid(w, d, file, std::nullopt, layout))
            throw Error("volume '" + w.name() + "': the file was written as a stream (no grid offsets) and holds a " + d.type +
                        " grid, which weft cannot check before OpenVDB reads it; re-save it as a regular .vdb file");
    }
}

VdbLayout walk(const char* data, std::uint64_t size, const std::string& name) {
    initVdb();  // the registered metadata types
    Walker w(data, size, name);
    VdbLayout layout;
    layout.fileSize = size;
    if (size < 8 || w.value<std::int64_t>("magic number") != kMagic) return layout;  // not a VDB: OpenVDB says so
    const std::uint32_t version = w.value<std::uint32_t>("file version");
    // Outside these versions OpenVDB reads lengths this walk cannot check
    // (a 40-byte header of version 0 made it allocate 1.7 GB), so the file is
    // refused rather than trusted.
    if (version < kOldestWalked || version > kNewestWalked)
        throw Error("volume '" + name + "': OpenVDB file format version " + std::to_string(version) +
                    " is not one weft reads (" + std::to_string(kOldestWalked) + " to " + std::to_string(kNewestWalked) +
                    "); re-save the file with a current OpenVDB");
    const std::uint32_t libraryMajor = w.value<std::uint32_t>("library major version");
    const std::uint32_t libraryMinor = w.value<std::uint32_t>("library minor version");
    const bool offsets = w.value<std::uint8_t>("grid offsets flag") != 0;
    if (version >= 218) w.skip(36, "file UUID");
    FileFormat file{version, 0, libraryMajor, libraryMinor};
    if (version < 222) file.compression = w.value<std::uint32_t>("file compression");
    walkMetadata(w, "file metadata");
    const std::int32_t grids = w.value<std::int32_t>("grid count");
    if (grids < 0 || std::uint64_t(grids) * 32 > w.left()) w.corrupt("grid count " + std::to_string(grids));
    if (offsets) walkIndexedGrids(w, file, grids, layout);
    else walkStreamedGrids(w, file, grids, layout);
    return layout;
}

// A file as it stands on disk: the same path with another inode, size or
// modification time is walked again.
using FileIdentity = std::tuple<std::string, dev_t, ino_t, off_t, time_t, long>;

// Files this process has walked and found sound, with their layouts: the
// density, its role grids and the grid-name lookup each open the same
// file, and one walk checks every grid in it.
struct WalkedFiles {
    std::mutex mutex;
    std::map<FileIdentity, std::shared_ptr<const VdbLayout>> files;
};

WalkedFiles& walkedFiles() {
    static WalkedFiles walked;
    return walked;
}

std::shared_ptr<const VdbLayout> walkedBefore(const FileIdentity& file) {
    WalkedFiles& walked = walkedFiles();
    std::lock_guard<std::mutex> lock(walked.mutex);
    const auto it = walked.files.find(file);
    return it == walked.files.end() ? nullptr : it->second;
}

void rememberWalked(const FileIdentity& file, std::shared_ptr<const VdbLayout> layout) {
    WalkedFiles& walked = walkedFiles();
    std::lock_guard<std::mutex> lock(walked.mutex);
    walked.files[file] = std::move(layout);
}

// The whole file in memory for the walk: mapped where the system can map
// it (only the pages the walk reads are loaded), read otherwise.
VdbLayout walkFile(int fd, std::uint64_t size, const std::string& path) {
    if (size == 0) return walk(nullptr, 0, path);
    const MappedFile mapped(fd, size);
    if (!mapped) {
        std::ifstream in(path, std::ios::binary);
        const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        return walk(bytes.data(), bytes.size(), path);
    }
    return walk(mapped.data(), size, path);
}

}  // namespace

std::shared_ptr<const VdbLayout> preflightVdb(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return nullptr;  // unreadable: the caller's open says so
    struct Close {
        int fd;
        ~Close() { ::close(fd); }
    } close{fd};
    struct stat st {};
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) return nullptr;  // the caller's checks name it
    const FileIdentity file{path, st.st_dev, st.st_ino, st.st_size, st.st_mtim.tv_sec, st.st_mtim.tv_nsec};
    if (auto layout = walkedBefore(file)) return layout;
    auto layout = std::make_shared<const VdbLayout>(walkFile(fd, std::uint64_t(st.st_size), path));
    rememberWalked(file, layout);
    return layout;
}

VdbLayout preflightVdbBytes(const std::string& bytes, const std::string& name) { return walk(bytes.data(), bytes.size(), name); }

}  // namespace weft
