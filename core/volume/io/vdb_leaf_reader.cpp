#include "core/volume/io/vdb_leaf_reader.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <openvdb/io/io.h>
#include <openvdb/tree/LeafManager.h>

#include <tbb/enumerable_thread_specific.h>

#include "core/base/error.hpp"
#include "core/base/files/mapped_file.hpp"

#include <atomic>
#include <istream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <streambuf>
#include <string>

namespace weft {

namespace {

// A file's bytes as a stream positioned anywhere: OpenVDB's readers take an istream.
class ByteBuffer : public std::streambuf {
public:
    ByteBuffer(const char* bytes, std::size_t size) : begin_(const_cast<char*>(bytes)), end_(begin_ + size) { setg(begin_, begin_, end_); }
    void seekTo(std::uint64_t pos) { setg(begin_, begin_ + pos, end_); }

protected:
    pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
        const off_type base = dir == std::ios_base::beg ? 0 : dir == std::ios_base::cur ? gptr() - begin_ : end_ - begin_;
        if (base + off < 0 || base + off > end_ - begin_) return pos_type(off_type(-1));
        setg(begin_, begin_ + base + off, end_);
        return pos_type(base + off);
    }
    pos_type seekpos(pos_type pos, std::ios_base::openmode mode) override { return seekoff(off_type(pos), std::ios_base::beg, mode); }

private:
    char* begin_;
    char* end_;
};

// Maps the file into `mapped` for the length of the load, when it still
// has the size the walk saw (leaves `mapped` empty otherwise).
void mapIfUnchanged(const std::string& path, std::uint64_t walkedSize, std::optional<MappedFile>& mapped) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    struct stat st {};
    if (fstat(fd, &st) == 0 && std::uint64_t(st.st_size) == walkedSize) mapped.emplace(fd, walkedSize);
    ::close(fd);
}

// One thread's stream over the mapped file, set up as OpenVDB's own grid
// read sets up its stream for a leaf buffer.
template <class GridT>
class LeafStream {
public:
    LeafStream(const MappedFile& bytes, const VdbGridLayout& layout, const GridT& grid)
        : buffer_(bytes.data(), bytes.size()), stream_(&buffer_), background_(grid.background()) {
        openvdb::io::setVersion(stream_, openvdb::VersionId(layout.libraryMajor, layout.libraryMinor), layout.fileVersion);
        openvdb::io::setDataCompression(stream_, layout.compression);
        openvdb::io::setGridBackgroundValuePtr(stream_, &background_);
    }
    // Decodes the leaf's buffer at `pos` into `leaf`, whose buffer is still in the file.
    void read(typename GridT::TreeType::LeafNodeType& leaf, std::uint64_t pos, bool half) {
        using Leaf = typename GridT::TreeType::LeafNodeType;
        buffer_.seekTo(pos);
        stream_.clear();
        Leaf decoded(openvdb::PartialCreate(), leaf.origin(), background_);
        decoded.readBuffers(stream_, half);
        if (!stream_ || decoded.getValueMask() != leaf.getValueMask())
            throw std::runtime_error("leaf buffer does not match its topology");
        leaf.buffer().swap(decoded.buffer());  // `decoded` leaves with the file record and releases it
    }

private:
    ByteBuffer buffer_;
    std::istream stream_;
    typename GridT::ValueType background_;
};

// Why the walk's record cannot place every leaf of the grid OpenVDB read, or
// "" when it can. OpenVDB's own delayed load of a leaf reads a raw chunk
// into its buffer before it checks the chunk's size, so a leaf OpenVDB
// placed by a corrupt file's metadata overflowed the heap (one byte changed
// in smoke_small.vdb crashed 3-6 runs in 10): such a leaf is never handed to it.
template <class TreeT>
std::string unplacedReason(const openvdb::tree::LeafManager<TreeT>& leaves, const MappedFile* bytes, const VdbGridLayout* layout) {
    if (!layout) return "the file's layout of the grid could not be read";
    if (!layout->unique) return "two grids of the file have its name";
    if (!bytes) return "the file changed while it was read";
    if (layout->leaves.size() != leaves.leafCount())
        return "its topology holds " + std::to_string(leaves.leafCount()) + " leaves, its buffers " + std::to_string(layout->leaves.size());
    for (std::size_t i = 0; i < leaves.leafCount(); ++i) {
        const vdbwalk::LeafBufferAt& at = layout->leaves[i];
        if (openvdb::Coord(at.origin[0], at.origin[1], at.origin[2]) != leaves.leaf(i).origin() || at.pos >= bytes->size())
            return "leaf " + std::to_string(i) + " is not where the file's buffers place it";
    }
    return "";
}

template <class GridT>
std::size_t loadLeavesOf(GridT& grid, const MappedFile* bytes, const VdbGridLayout* layout) {
    using TreeT = typename GridT::TreeType;
    openvdb::tree::LeafManager<TreeT> leaves(grid.tree());
    bool outOfCore = false;
    for (std::size_t i = 0; i < leaves.leafCount() && !outOfCore; ++i) outOfCore = leaves.leaf(i).buffer().isOutOfCore();
    if (!outOfCore) return 0;  // read whole already: nothing is left to decode
    if (const std::string why = unplacedReason(leaves, bytes, layout); !why.empty()) throw Error(why);
    tbb::enumerable_thread_specific<std::unique_ptr<LeafStream<GridT>>> streams;
    std::atomic<std::size_t> decoded{0};
    leaves.foreach([&](typename TreeT::LeafNodeType& leaf, std::size_t i) {
        if (!leaf.buffer().isOutOfCore()) return;
        const vdbwalk::LeafBufferAt& at = layout->leaves[i];
        std::unique_ptr<LeafStream<GridT>>& stream = streams.local();
        if (!stream) stream = std::make_unique<LeafStream<GridT>>(*bytes, *layout, grid);
        stream->read(leaf, at.pos, layout->half);
        decoded.fetch_add(1, std::memory_order_relaxed);
    });
    return decoded.load();
}

}  // namespace

std::size_t loadLeaves(const openvdb::GridBase::Ptr& grid, const std::string& path, const VdbLayout* file, const VdbGridLayout* layout) {
    std::optional<MappedFile> bytes;
    if (file && layout) mapIfUnchanged(path, file->fileSize, bytes);
    const MappedFile* mapped = bytes && *bytes ? &*bytes : nullptr;
    if (auto floats = openvdb::gridPtrCast<openvdb::FloatGrid>(grid)) return loadLeavesOf(*floats, mapped, layout);
    if (auto vectors = openvdb::gridPtrCast<openvdb::Vec3SGrid>(grid)) return loadLeavesOf(*vectors, mapped, layout);
    return 0;
}

}  // namespace weft
