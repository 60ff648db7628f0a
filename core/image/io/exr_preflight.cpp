#include "core/image/io/exr_preflight.hpp"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/base/error.hpp"
#include "core/base/quote_value.hpp"

namespace weft {

namespace {

constexpr std::uint32_t kMultiPartFlag = 0x1000;

// Scanlines per chunk of each compression (OpenEXR's Compression enum order).
int linesPerBlock(int compression) {
    constexpr int lines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
    return compression >= 0 && compression < int(std::size(lines)) ? lines[compression] : 1;
}

class HeaderReader {
public:
    explicit HeaderReader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
        std::error_code ec;
        size_ = std::filesystem::file_size(path, ec);
        if (!in_ || ec) fail("cannot be read");
    }

    [[noreturn]] void fail(const std::string& what) const { throw Error("image '" + path_ + "': cannot be read: " + what); }
    std::uint64_t left() const { return size_ - pos_; }

    void bytes(void* out, std::uint64_t n, const char* what) {
        if (n > left()) fail(std::string("the file ends inside its header (") + what + ")");
        in_.read(static_cast<char*>(out), std::streamsize(n));
        pos_ += n;
    }
    std::uint32_t u32(const char* what) {
        unsigned char b[4];
        bytes(b, 4, what);
        return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
    }
    // A NUL-terminated name of at most 255 characters ("" ends a header).
    std::string name(const char* what) {
        std::string s;
        for (char c = 0;;) {
            bytes(&c, 1, what);
            if (c == '\0') return s;
            if (s.size() == 255) fail(std::string("an attribute ") + what + " longer than 255 characters");
            s += c;
        }
    }
    void skip(std::uint64_t n) {
        in_.seekg(std::streamoff(n), std::ios::cur);
        pos_ += n;
    }

private:
    std::string path_;
    std::ifstream in_;
    std::uint64_t size_ = 0, pos_ = 0;
};

struct PartFacts {
    bool hasWindow = false, hasDisplay = false, hasTiles = false, hasChunkCount = false;
    std::int32_t window[4] = {0, 0, 0, 0};
    std::int32_t display[4] = {0, 0, 0, 0};
    std::uint64_t channels = 0;
    std::uint32_t tile[2] = {1, 1};
    int compression = 0;
    std::uint64_t chunkCount = 0;
};

// Sums and products of declared sizes saturate: a header may claim 2^64.
std::uint64_t saturatingMul(std::uint64_t a, std::uint64_t b) { return b && a > UINT64_MAX / b ? UINT64_MAX : a * b; }
std::uint64_t saturatingAdd(std::uint64_t a, std::uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }

bool printable(const std::string& s) {
    for (unsigned char c : s)
        if (c < 0x20 || c >= 0x7f) return false;
    return true;
}

// The byte sizes of the attribute types whose values OpenEXR reads field by
// field, whatever size the attribute states: a size that differs would make
// OpenEXR read a different header than this walk (a dataWindow hidden
// inside a longer attribute, say), so it is refused.
int fixedSizeOf(const std::string& type) {
    static const std::pair<const char*, int> sizes[] = {
        {"box2i", 16}, {"box2f", 16}, {"int", 4}, {"float", 4}, {"double", 8}, {"v2i", 8}, {"v2f", 8},
        {"v2d", 16}, {"v3i", 12}, {"v3f", 12}, {"v3d", 24}, {"m33f", 36}, {"m44f", 64}, {"m33d", 72},
        {"m44d", 128}, {"compression", 1}, {"lineOrder", 1}, {"envmap", 1}, {"deepImageState", 1},
        {"tiledesc", 9}, {"chromaticities", 32}, {"keycode", 28}, {"timecode", 8}, {"rational", 8}};
    for (const auto& [name, size] : sizes)
        if (type == name) return size;
    return -1;
}

// A chlist is a list of (name, 16 bytes of layout) ended by an empty name,
// read by OpenEXR up to that empty name: it must end exactly where the
// attribute's size says.
std::uint64_t countChannels(HeaderReader& r, std::uint32_t size) {
    std::string bytes(size, '\0');
    r.bytes(bytes.data(), size, "channels");
    std::uint64_t count = 0;
    std::size_t at = 0;
    for (; at < bytes.size() && bytes[at] != '\0'; ++count) {
        const std::size_t end = bytes.find('\0', at);
        if (end == std::string::npos || end + 1 + 16 > bytes.size()) break;
        at = end + 1 + 16;
    }
    // The list's empty name must be the attribute's last byte: a last name
    // cut short by the size leaves `at` there too, on a byte that is no NUL.
    if (at + 1 != bytes.size() || bytes[at] != '\0')
        r.fail("the channel list does not end where its attribute's " + std::to_string(size) + " bytes end (corrupt)");
    return count;
}

// A stringvector is (32-bit length, characters) pairs, read by OpenEXR
// until it has read the attribute's size: each string must fit in what is
// left, or OpenEXR allocates its length and reads past the attribute.
void walkStringVector(HeaderReader& r, std::uint32_t size) {
    std::uint64_t left = size;
    while (left > 0) {
        if (left < 4) r.fail("a stringvector attribute of " + std::to_string(size) + " bytes ends inside a length (corrupt)");
        const std::uint32_t length = r.u32("stringvector");
        left -= 4;
        if (length > left)
            r.fail("a stringvector string of " + std::to_string(length) + " bytes in the " + std::to_string(left) +
                   " left of its attribute (corrupt)");
        r.skip(length);
        left -= length;
    }
}

void readValue(HeaderReader& r, const std::string& name, const std::string& type, std::uint32_t size, PartFacts& f) {
    const int fixed = fixedSizeOf(type);
    if (fixed >= 0 && size != std::uint32_t(fixed))
        r.fail("an attribute of type " + (printable(type) ? quoteValue(type) : std::string("?")) + " holds " +
               std::to_string(size) + " bytes instead of " + std::to_string(fixed) + " (corrupt)");
    if (name == "dataWindow" && type == "box2i") {
        for (std::int32_t& v : f.window) v = std::int32_t(r.u32("dataWindow"));
        f.hasWindow = true;
    } else if (name == "displayWindow" && type == "box2i") {
        for (std::int32_t& v : f.display) v = std::int32_t(r.u32("displayWindow"));
        f.hasDisplay = true;
    } else if (type == "chlist") {
        const std::uint64_t channels = countChannels(r, size);
        if (name == "channels") f.channels = channels;
    } else if (type == "preview") {  // OpenEXR allocates width x height RGBA pixels from these two words
        if (size < 8) r.fail("a preview attribute of " + std::to_string(size) + " bytes (corrupt)");
        const std::uint64_t w = r.u32("preview"), h = r.u32("preview");
        if (saturatingMul(saturatingMul(w, h), 4) != size - 8u)
            r.fail("a preview image of " + std::to_string(w) + "x" + std::to_string(h) + " in " + std::to_string(size) +
                   " bytes (corrupt)");
        r.skip(size - 8u);
    } else if (type == "stringvector") {
        walkStringVector(r, size);
    } else if (name == "tiles" && type == "tiledesc") {
        f.tile[0] = r.u32("tiles"), f.tile[1] = r.u32("tiles");
        r.skip(1);
        f.hasTiles = true;
    } else if (name == "compression" && type == "compression") {
        unsigned char c = 0;
        r.bytes(&c, 1, "compression");
        f.compression = c;
    } else if (name == "chunkCount" && type == "int") {
        f.chunkCount = r.u32("chunkCount");
        f.hasChunkCount = true;
    } else {
        r.skip(size);
    }
}

// One header's attributes; false when it is the empty header ending a multi-part file's list.
bool readHeader(HeaderReader& r, PartFacts& f) {
    for (int count = 0;; ++count) {
        const std::string name = r.name("name");
        if (name.empty()) return count > 0;
        const std::string type = r.name("type");
        const std::uint32_t size = r.u32("attribute size");
        if (size > r.left())
            r.fail((printable(name) && printable(type) ? "attribute " + quoteValue(name) + " (" + quoteValue(type) + ")"
                                                       : std::string("an attribute with a corrupt name")) +
                   " claims " + std::to_string(size) + " bytes, more than the " + std::to_string(r.left()) +
                   " left in the file (corrupt or cut short)");
        readValue(r, name, type, size, f);
    }
}

// The area of a box2i (x min, y min, x max, y max); 0 when it is empty.
std::uint64_t areaOf(const std::int32_t box[4]) {
    const std::int64_t w = std::int64_t(box[2]) - box[0] + 1, h = std::int64_t(box[3]) - box[1] + 1;
    return w > 0 && h > 0 ? saturatingMul(std::uint64_t(w), std::uint64_t(h)) : 0;
}

// The chunks the part's offset table lists (a lower bound for mip-mapped tiles).
std::uint64_t chunksOf(const PartFacts& f) {
    if (f.hasChunkCount) return f.chunkCount;
    if (!f.hasWindow) return 0;
    const std::int64_t w = std::int64_t(f.window[2]) - f.window[0] + 1, h = std::int64_t(f.window[3]) - f.window[1] + 1;
    if (w <= 0 || h <= 0) return 0;  // OpenEXR refuses it with its own message
    if (f.hasTiles && f.tile[0] > 0 && f.tile[1] > 0)
        return std::uint64_t((w + f.tile[0] - 1) / f.tile[0]) * std::uint64_t((h + f.tile[1] - 1) / f.tile[1]);
    return std::uint64_t((h + linesPerBlock(f.compression) - 1) / linesPerBlock(f.compression));
}

}  // namespace

ExrDeclared preflightExr(const std::string& path) {
    HeaderReader r(path);
    ExrDeclared declared;
    if (r.u32("magic number") != 20000630u) r.fail("not an EXR file (no EXR magic number)");
    const bool multiPart = r.u32("version") & kMultiPartFlag;
    std::uint64_t chunks = 0;
    for (int part = 0;; ++part) {
        PartFacts f;
        if (!readHeader(r, f)) break;
        chunks += chunksOf(f);
        const std::uint64_t area = f.hasWindow ? areaOf(f.window) : 0;
        declared.dataPixels = saturatingAdd(declared.dataPixels, area);
        declared.displayPixels = saturatingAdd(declared.displayPixels, f.hasDisplay ? areaOf(f.display) : 0);
        declared.pixelValues = saturatingAdd(declared.pixelValues, saturatingMul(area, f.channels));
        if (!multiPart) break;
    }
    if (chunks > r.left() / 8)
        r.fail("its header needs an offset table of " + std::to_string(chunks) + " chunks (8 bytes each), more than the " +
               std::to_string(r.left()) + " bytes left in the file (corrupt or cut short)");
    return declared;
}

}  // namespace weft
