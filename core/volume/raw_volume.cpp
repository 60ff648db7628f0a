#include "core/volume/raw_volume.hpp"

#include <openvdb/tools/Dense.h>

#include <boost/iostreams/filter/gzip.hpp>
#include <boost/iostreams/filtering_stream.hpp>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/base/error.hpp"
#include "core/base/input_file.hpp"
#include "core/volume/volume.hpp"

namespace fs = std::filesystem;
namespace bio = boost::iostreams;

namespace weft {

namespace {

std::vector<std::string> splitCommas(const std::string& text) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = text.find(',', start);
        parts.push_back(text.substr(start, comma - start));
        if (comma == std::string::npos) return parts;
        start = comma + 1;
    }
}

// from_chars wants the whole field: "12abc" or " 12" are not numbers.
template <class T>
bool parseWhole(const std::string& field, T& value) {
    const char* end = field.data() + field.size();
    const auto [ptr, ec] = std::from_chars(field.data(), end, value);
    return !field.empty() && ec == std::errc() && ptr == end;
}

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string coordText(const openvdb::Coord& c) {
    return std::to_string(c.x()) + "," + std::to_string(c.y()) + "," + std::to_string(c.z());
}

// ---- reading ---------------------------------------------------------------

// The file's bytes, through a gzip decompressor when it is compressed.
// Stream errors throw (badbit) so corrupt data is never mistaken for an end.
class RawSource {
public:
    RawSource(const std::string& path, bool gzip) : file_(path, std::ios::binary) {
        if (!file_) throw Error(path + ": cannot open: " + std::strerror(errno));
        if (gzip) stream_.push(bio::gzip_decompressor());
        stream_.push(file_);
        stream_.exceptions(std::ios::badbit);
    }

    // Fills dst with up to n bytes; fewer only at the end of the data.
    std::size_t read(unsigned char* dst, std::size_t n) {
        stream_.read(reinterpret_cast<char*>(dst), std::streamsize(n));
        return std::size_t(stream_.gcount());
    }

    // Drains what is left, to report the true size of an oversized file.
    std::uint64_t countRest() {
        std::vector<char> sink(1 << 16);
        std::uint64_t total = 0;
        while (stream_) {
            stream_.read(sink.data(), std::streamsize(sink.size()));
            total += std::uint64_t(stream_.gcount());
        }
        return total;
    }

private:
    std::ifstream file_;
    bio::filtering_istream stream_;
};

Error sizeMismatch(const std::string& path, bool gzip, std::uint64_t held, const RawVolumeSpec& spec) {
    return Error(path + ": " + (gzip ? "unpacks to " : "holds ") + std::to_string(held) + " bytes but " +
                 describeRawSpec(spec) + " needs " + std::to_string(rawByteCount(spec)));
}

std::string gzipProblem(const bio::gzip_error& e) {
    switch (e.error()) {
        case bio::gzip::bad_header: return "not gzip data (bad header)";
        case bio::gzip::bad_crc: return "corrupt gzip data (checksum mismatch)";
        case bio::gzip::bad_length: return "corrupt gzip data (length mismatch)";
        case bio::gzip::bad_footer: return "truncated or corrupt gzip data (bad footer)";
        case bio::gzip::zlib_error:
            // zlib runs out of input mid-stream when the file was cut short.
            if (e.zlib_error_code() == bio::zlib::buf_error) return "truncated gzip data (the stream ends early)";
            return "corrupt gzip data (zlib error " + std::to_string(e.zlib_error_code()) + ")";
        default: return std::string("corrupt gzip data (") + e.what() + ")";
    }
}

template <class U>
U swapBytes(U v) {
    U out = 0;
    for (std::size_t i = 0; i < sizeof(U); ++i) out = U((out << 8) | ((v >> (8 * i)) & 0xff));
    return out;
}

template <class U>
U loadWord(const unsigned char* p, bool swap) {
    U v;
    std::memcpy(&v, p, sizeof(U));
    return swap ? swapBytes(v) : v;
}

// Turns n samples into floats. Returns the index of the first non-finite
// sample (only f32 can hold one), or n.
std::size_t decodeSamples(const unsigned char* in, float* out, std::size_t n, RawType type, bool swap) {
    switch (type) {
        case RawType::U8:
            for (std::size_t i = 0; i < n; ++i) out[i] = float(in[i]);
            return n;
        case RawType::U16:
            for (std::size_t i = 0; i < n; ++i) out[i] = float(loadWord<std::uint16_t>(in + 2 * i, swap));
            return n;
        case RawType::F32:
            for (std::size_t i = 0; i < n; ++i) {
                out[i] = std::bit_cast<float>(loadWord<std::uint32_t>(in + 4 * i, swap));
                if (!std::isfinite(out[i])) return i;
            }
            return n;
    }
    return n;
}

// z-slices converted per copyFromDense call: a multiple of the leaf size (8)
// so no leaf node straddles two slabs, and about 4M voxels to keep memory
// flat while giving the threads enough blocks.
int slabDepth(std::uint64_t sliceVoxels, int depth) {
    const std::uint64_t target = std::uint64_t(1) << 22;
    const std::uint64_t slices = std::max<std::uint64_t>(8, target / sliceVoxels / 8 * 8);
    return int(std::min<std::uint64_t>(slices, std::uint64_t(depth)));
}

openvdb::math::Transform::Ptr spacingTransform(const openvdb::Vec3d& s) {
    if (s.x() == s.y() && s.y() == s.z()) return openvdb::math::Transform::createLinearTransform(s.x());
    return std::make_shared<openvdb::math::Transform>(std::make_shared<openvdb::math::ScaleMap>(s));
}

}  // namespace

// ---- options ---------------------------------------------------------------

openvdb::Coord parseRawDims(const std::string& text) {
    const std::vector<std::string> parts = splitCommas(text);
    const Error bad("--dims '" + text + "': expected 3 positive integers X,Y,Z (e.g. 256,256,128)");
    if (parts.size() != 3) throw bad;
    std::int64_t d[3];
    for (int i = 0; i < 3; ++i) {
        if (!parseWhole(parts[i], d[i])) {
            // Digits only yet not parsed: an integer too large for 64 bits.
            if (!parts[i].empty() && parts[i].find_first_not_of("0123456789") == std::string::npos) d[i] = kMaxRawDim + 1;
            else throw bad;
        }
        if (d[i] <= 0) throw bad;
        if (d[i] > kMaxRawDim)
            throw Error("--dims '" + text + "': " + parts[i] + " voxels along an axis is more than weft accepts (" +
                        std::to_string(kMaxRawDim) + ")");
    }
    return openvdb::Coord(int(d[0]), int(d[1]), int(d[2]));
}

openvdb::Vec3d parseRawSpacing(const std::string& text) {
    const std::vector<std::string> parts = splitCommas(text);
    const Error bad("--spacing '" + text + "': expected 3 positive numbers sx,sy,sz (e.g. 1,1,2.5)");
    if (parts.size() != 3) throw bad;
    openvdb::Vec3d s;
    for (int i = 0; i < 3; ++i)
        if (!parseWhole(parts[i], s[i]) || !std::isfinite(s[i]) || !(s[i] > 0)) throw bad;
    return s;
}

RawType parseRawType(const std::string& text) {
    if (text == "u8") return RawType::U8;
    if (text == "u16") return RawType::U16;
    if (text == "f32") return RawType::F32;
    throw Error("--type '" + text + "': unknown sample type (expected u8|u16|f32)");
}

ByteOrder parseByteOrder(const std::string& text) {
    if (text == "little") return ByteOrder::Little;
    if (text == "big") return ByteOrder::Big;
    throw Error("--endian '" + text + "': unknown byte order (expected little|big)");
}

const char* rawTypeName(RawType type) {
    switch (type) {
        case RawType::U8: return "u8";
        case RawType::U16: return "u16";
        case RawType::F32: return "f32";
    }
    return "?";
}

std::size_t rawTypeBytes(RawType type) {
    switch (type) {
        case RawType::U8: return 1;
        case RawType::U16: return 2;
        case RawType::F32: return 4;
    }
    return 0;
}

std::string describeRawSpec(const RawVolumeSpec& spec) {
    return "--dims " + coordText(spec.dims) + " --type " + rawTypeName(spec.type);
}

std::uint64_t rawByteCount(const RawVolumeSpec& spec) {
    if (spec.dims.x() <= 0 || spec.dims.y() <= 0 || spec.dims.z() <= 0)
        throw Error(describeRawSpec(spec) + ": every dimension must be positive");
    std::uint64_t bytes = rawTypeBytes(spec.type);
    for (int i = 0; i < 3; ++i)
        if (__builtin_mul_overflow(bytes, std::uint64_t(spec.dims[i]), &bytes))
            throw Error(describeRawSpec(spec) + ": the volume size overflows 64 bits");
    if (bytes > kMaxRawBytes)
        throw Error(describeRawSpec(spec) + " needs " + std::to_string(bytes) +
                    " bytes, more than the 1 TiB weft accepts");
    return bytes;
}

// ---- conversion ------------------------------------------------------------

openvdb::FloatGrid::Ptr readRawVolume(const std::string& path, const RawVolumeSpec& spec) {
    initVdb();
    const std::uint64_t needed = rawByteCount(spec);
    if (spec.gridName.empty()) throw Error("--grid: the grid name must not be empty");
    requireRegularFile(path, "raw volume");
    const bool gzip = endsWith(path, ".gz");
    // A plain file's size is known up front: fail before reading anything.
    if (!gzip) {
        std::error_code ec;
        const std::uint64_t held = fs::file_size(path, ec);
        if (ec) throw Error(path + ": cannot read its size: " + ec.message());
        if (held != needed) throw sizeMismatch(path, false, held, spec);
    }

    const int nx = spec.dims.x(), ny = spec.dims.y(), nz = spec.dims.z();
    const std::size_t sampleBytes = rawTypeBytes(spec.type);
    const std::uint64_t sliceVoxels = std::uint64_t(nx) * std::uint64_t(ny);
    const int depth = slabDepth(sliceVoxels, nz);
    const bool swap = (spec.byteOrder == ByteOrder::Big) != (std::endian::native == std::endian::big);

    auto grid = openvdb::FloatGrid::create(0.0f);
    std::vector<unsigned char> bytes(sliceVoxels * std::uint64_t(depth) * sampleBytes);
    std::vector<float> values(sliceVoxels * std::uint64_t(depth));
    std::uint64_t consumed = 0;
    try {
        RawSource source(path, gzip);
        for (int z0 = 0; z0 < nz; z0 += depth) {
            const int slices = std::min(depth, nz - z0);
            const std::size_t count = sliceVoxels * std::uint64_t(slices);
            const std::size_t got = source.read(bytes.data(), count * sampleBytes);
            consumed += got;
            if (got < count * sampleBytes) throw sizeMismatch(path, gzip, consumed, spec);
            const std::size_t bad = decodeSamples(bytes.data(), values.data(), count, spec.type, swap);
            if (bad < count) {
                const openvdb::Coord at(int(bad % nx), int(bad / nx % ny), z0 + int(bad / sliceVoxels));
                throw Error(path + ": voxel (" + coordText(at) + ") holds " + std::to_string(values[bad]) +
                            "; densities must be finite (is --type or --endian wrong?)");
            }
            const openvdb::CoordBBox box(openvdb::Coord(0, 0, z0), openvdb::Coord(nx - 1, ny - 1, z0 + slices - 1));
            openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, values.data());
            openvdb::tools::copyFromDense(dense, grid->tree(), 0.0f);
        }
        if (gzip) {
            const std::uint64_t extra = source.countRest();
            if (extra > 0) throw sizeMismatch(path, true, consumed + extra, spec);
        }
    } catch (const bio::gzip_error& e) {
        throw Error(path + ": " + gzipProblem(e));
    } catch (const std::ios_base::failure& e) {
        throw Error(path + ": " + (gzip ? "corrupt gzip data (" : "read error (") + e.what() + ")");
    }

    grid->setName(spec.gridName);
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(spacingTransform(spec.spacing));
    grid->setSaveFloatAsHalf(false);
    return grid;
}

}  // namespace weft
