#include "core/volume/io/raw_samples.hpp"

#include <openvdb/tools/Dense.h>

#include <boost/iostreams/filter/gzip.hpp>
#include <boost/iostreams/filtering_stream.hpp>

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <type_traits>
#include <vector>

#include "core/base/error.hpp"
#include "core/base/files/input_file.hpp"
#include "core/volume/grid/vdb_init.hpp"
#include "core/volume/io/header_text.hpp"

namespace fs = std::filesystem;
namespace bio = boost::iostreams;

namespace weft {

namespace {

std::string coordText(const openvdb::Coord& c) {
    return std::to_string(c.x()) + "," + std::to_string(c.y()) + "," + std::to_string(c.z());
}

// ---- byte sources ------------------------------------------------------------

// The file's bytes from an offset on, through a gzip decompressor when they
// are compressed. Stream errors throw (badbit) so corrupt data is never
// mistaken for an end.
class RawSource {
public:
    RawSource(const RawDataSource& src) : file_(src.path, std::ios::binary) {
        if (!file_) throw Error(src.path + ": cannot open: " + std::strerror(errno));
        file_.seekg(std::streamoff(src.offset));
        if (src.encoding == SampleEncoding::Gzip) stream_.push(bio::gzip_decompressor());
        stream_.push(file_);
        stream_.exceptions(std::ios::badbit);
    }

    // Fills dst with up to n bytes; fewer only at the end of the data.
    std::size_t read(unsigned char* dst, std::size_t n) {
        stream_.read(reinterpret_cast<char*>(dst), std::streamsize(n));
        return std::size_t(stream_.gcount());
    }

    // Reads and drops up to n bytes; returns how many there were.
    std::uint64_t skip(std::uint64_t n) {
        std::vector<char> sink(1 << 16);
        std::uint64_t total = 0;
        while (total < n && stream_) {
            stream_.read(sink.data(), std::streamsize(std::min<std::uint64_t>(sink.size(), n - total)));
            total += std::uint64_t(stream_.gcount());
        }
        return total;
    }

    // Drains what is left, to report the true size of an oversized file.
    std::uint64_t countRest() { return skip(~std::uint64_t(0)); }

    // The next whitespace-separated word, at most 64 characters; empty at the end.
    std::string word(const std::string& path) {
        std::streambuf& in = *stream_.rdbuf();
        int c = in.sgetc();
        while (c == ' ' || c == '\t' || c == '\r' || c == '\n') c = in.snextc();
        std::string w;
        while (c != std::char_traits<char>::eof() && c != ' ' && c != '\t' && c != '\r' && c != '\n') {
            if (w.size() == 64) throw Error(path + ": a sample of more than 64 characters ('" + w.substr(0, 20) + "...')");
            w.push_back(char(c));
            c = in.snextc();
        }
        return w;
    }

private:
    std::ifstream file_;
    bio::filtering_istream stream_;
};

std::string describe(const RawDataSource& src, const RawVolumeSpec& spec) {
    return src.describedBy.empty() ? describeRawSpec(spec) : src.describedBy;
}

Error sizeMismatch(const RawDataSource& src, std::uint64_t held, const RawVolumeSpec& spec) {
    const bool gzip = src.encoding == SampleEncoding::Gzip;
    std::string where = src.offset > 0 ? " after its " + std::to_string(src.offset) + "-byte header" : "";
    if (src.skipDecoded > 0) where += " and " + std::to_string(src.skipDecoded) + " skipped bytes";
    return Error(src.path + ": " + (gzip ? "unpacks to " : "holds ") + std::to_string(held) + " bytes" + where +
                 " but " + describe(src, spec) + " needs " + std::to_string(rawByteCount(spec)));
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

// ---- decoding --------------------------------------------------------------

template <std::size_t N> struct WordOf;
template <> struct WordOf<1> { using type = std::uint8_t; };
template <> struct WordOf<2> { using type = std::uint16_t; };
template <> struct WordOf<4> { using type = std::uint32_t; };
template <> struct WordOf<8> { using type = std::uint64_t; };

template <class U>
U swapBytes(U v) {
    if constexpr (sizeof(U) == 1) return v;
    else if constexpr (sizeof(U) == 2) return __builtin_bswap16(v);
    else if constexpr (sizeof(U) == 4) return __builtin_bswap32(v);
    else return __builtin_bswap64(v);
}

template <class T>
T loadSample(const unsigned char* p, bool swap) {
    using U = typename WordOf<sizeof(T)>::type;
    U u;
    std::memcpy(&u, p, sizeof(U));
    return std::bit_cast<T>(swap ? swapBytes(u) : u);
}

// What a float grid can hold: finite, and within float range (a double
// beyond it would become infinite).
template <class T>
bool fitsFloat(T v) {
    if constexpr (std::is_floating_point_v<T>) return std::isfinite(v) && std::fabs(double(v)) <= double(FLT_MAX);
    else return true;
}

// Turns n samples into floats (integers beyond 2^24 round to the nearest
// float). Returns the index of the first sample a float cannot hold, or n.
template <class T>
std::size_t decodeAs(const unsigned char* in, float* out, std::size_t n, bool swap) {
    for (std::size_t i = 0; i < n; ++i) {
        const T v = loadSample<T>(in + sizeof(T) * i, swap);
        if (!fitsFloat(v)) return i;
        out[i] = float(v);
    }
    return n;
}

template <class F>
auto dispatchType(RawType type, F&& f) {
    switch (type) {
        case RawType::U8: return f(std::uint8_t{});
        case RawType::I8: return f(std::int8_t{});
        case RawType::U16: return f(std::uint16_t{});
        case RawType::I16: return f(std::int16_t{});
        case RawType::U32: return f(std::uint32_t{});
        case RawType::I32: return f(std::int32_t{});
        case RawType::F32: return f(float{});
        case RawType::F64: return f(double{});
    }
    return f(std::uint8_t{});
}

std::size_t decodeSamples(const unsigned char* in, float* out, std::size_t n, RawType type, bool swap) {
    return dispatchType(type, [&](auto t) { return decodeAs<decltype(t)>(in, out, n, swap); });
}

double sampleAsDouble(const unsigned char* in, RawType type, bool swap) {
    return dispatchType(type, [&](auto t) { return double(loadSample<decltype(t)>(in, swap)); });
}

// One decimal sample of an ASCII file as the type would hold it: integers
// must be whole and in the type's range, floats within float range.
bool parseAsciiSample(const std::string& word, RawType type, float& out) {
    return dispatchType(type, [&](auto t) {
        using T = decltype(t);
        T v;
        if constexpr (std::is_same_v<T, std::uint8_t> || std::is_same_v<T, std::int8_t>) {
            int wide;
            if (!parseWhole(word, wide) || wide < int(std::numeric_limits<T>::min()) || wide > int(std::numeric_limits<T>::max()))
                return false;
            v = T(wide);
        } else if (!parseWhole(word, v) || !fitsFloat(v)) {
            return false;
        }
        out = float(v);
        return true;
    });
}

openvdb::Coord voxelAt(const openvdb::Coord& dims, int z0, std::size_t index) {
    const std::size_t nx = std::size_t(dims.x()), ny = std::size_t(dims.y());
    return openvdb::Coord(int(index % nx), int(index / nx % ny), z0 + int(index / (nx * ny)));
}

std::string valueText(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%g", v);
    return std::isfinite(v) ? std::string(buf) : std::to_string(v);
}

// ---- grid building ---------------------------------------------------------

// z-slices converted per copyFromDense call: a multiple of the leaf size (8)
// so no leaf node straddles two slabs, and about 4M voxels to keep memory
// flat while giving the threads enough blocks.
int slabDepth(std::uint64_t sliceVoxels, int depth) {
    const std::uint64_t target = std::uint64_t(1) << 22;
    const std::uint64_t slices = std::max<std::uint64_t>(8, target / sliceVoxels / 8 * 8);
    return int(std::min<std::uint64_t>(slices, std::uint64_t(depth)));
}

// fill(z0, count, values) writes the next `count` samples (x fastest) of the
// slab starting at slice z0, or throws.
using SlabFill = std::function<void(int z0, std::size_t count, float* values)>;

openvdb::FloatGrid::Ptr buildGrid(const RawVolumeSpec& spec, const SlabFill& fill) {
    const int nx = spec.dims.x(), ny = spec.dims.y(), nz = spec.dims.z();
    const std::uint64_t sliceVoxels = std::uint64_t(nx) * std::uint64_t(ny);
    const int depth = slabDepth(sliceVoxels, nz);
    const float background = float(spec.background);
    auto grid = openvdb::FloatGrid::create(background);
    std::vector<float> values(sliceVoxels * std::uint64_t(depth));
    for (int z0 = 0; z0 < nz; z0 += depth) {
        const int slices = std::min(depth, nz - z0);
        fill(z0, sliceVoxels * std::uint64_t(slices), values.data());
        const openvdb::CoordBBox box(openvdb::Coord(0, 0, z0), openvdb::Coord(nx - 1, ny - 1, z0 + slices - 1));
        openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, values.data());
        // Tolerance 0: exactly the background value is inactive.
        openvdb::tools::copyFromDense(dense, grid->tree(), 0.0f);
    }
    return grid;
}

// Bytes the file holds after its header.
std::uint64_t bytesAfterHeader(const RawDataSource& src) {
    std::error_code ec;
    const std::uint64_t size = fs::file_size(src.path, ec);
    if (ec) throw Error(src.path + ": cannot read its size: " + ec.message());
    if (size < src.offset) throw Error(src.path + ": the file ends inside its " + std::to_string(src.offset) + "-byte header");
    return size - src.offset;
}

void checkSourceSize(const RawDataSource& src, const RawVolumeSpec& spec, std::uint64_t needed) {
    const std::uint64_t held = bytesAfterHeader(src);
    if (held < needed || (held > needed && !src.trailingAllowed)) throw sizeMismatch(src, held, spec);
}

// Data whose size is not known up front is still bounded before anything is
// allocated: deflate packs at most 1032 bytes into one, and a sample written
// as text takes at least two bytes (a digit and a separator).
void checkPackedSize(const RawDataSource& src, const RawVolumeSpec& spec, std::uint64_t needed) {
    const std::uint64_t held = bytesAfterHeader(src);
    const std::string after = src.offset > 0 ? " after its " + std::to_string(src.offset) + "-byte header" : "";
    if (src.encoding == SampleEncoding::Gzip && (needed + src.skipDecoded) / 1032 > held + 64)
        throw Error(src.path + ": " + std::to_string(held) + " bytes of gzip data" + after + " cannot unpack to the " +
                    std::to_string(needed) + " bytes " + describe(src, spec) + " needs");
    const std::uint64_t samples = needed / rawTypeBytes(spec.type);
    if (src.encoding == SampleEncoding::Ascii && samples > held / 2 + 1)
        throw Error(src.path + ": holds " + std::to_string(held) + " bytes" + after + ", too few for the " +
                    std::to_string(samples) + " text samples " + describe(src, spec) + " needs");
}

openvdb::FloatGrid::Ptr readBinary(const RawDataSource& src, const RawVolumeSpec& spec) {
    const bool gzip = src.encoding == SampleEncoding::Gzip;
    const std::size_t sampleBytes = rawTypeBytes(spec.type);
    const bool swap = (spec.byteOrder == ByteOrder::Big) != (std::endian::native == std::endian::big);
    RawSource source(src);
    if (src.skipDecoded > 0 && source.skip(src.skipDecoded) < src.skipDecoded)
        throw Error(src.path + ": the data ends inside its " + std::to_string(src.skipDecoded) + " skipped bytes");
    std::vector<unsigned char> bytes;
    std::uint64_t consumed = 0;
    auto grid = buildGrid(spec, [&](int z0, std::size_t count, float* values) {
        bytes.resize(count * sampleBytes);
        const std::size_t got = source.read(bytes.data(), bytes.size());
        consumed += got;
        if (got < bytes.size()) throw sizeMismatch(src, consumed, spec);
        const std::size_t bad = decodeSamples(bytes.data(), values, count, spec.type, swap);
        if (bad == count) return;
        const double v = sampleAsDouble(bytes.data() + bad * sampleBytes, spec.type, swap);
        throw Error(src.path + ": voxel (" + coordText(voxelAt(spec.dims, z0, bad)) + ") holds " + valueText(v) +
                    (std::isfinite(v) ? ", beyond float range; weft's grids hold floats (is --type or --endian wrong?)"
                                      : "; densities must be finite (is --type or --endian wrong?)"));
    });
    if (gzip && !src.trailingAllowed) {
        const std::uint64_t extra = source.countRest();
        if (extra > 0) throw sizeMismatch(src, consumed + extra, spec);
    }
    return grid;
}

openvdb::FloatGrid::Ptr readAscii(const RawDataSource& src, const RawVolumeSpec& spec) {
    RawSource source(src);
    std::uint64_t seen = 0;
    return buildGrid(spec, [&](int z0, std::size_t count, float* values) {
        for (std::size_t i = 0; i < count; ++i, ++seen) {
            const std::string word = source.word(src.path);
            if (word.empty())
                throw Error(src.path + ": holds " + std::to_string(seen) + " samples but " + describe(src, spec) + " needs " +
                            std::to_string(std::uint64_t(spec.dims.x()) * spec.dims.y() * spec.dims.z()));
            if (!parseAsciiSample(word, spec.type, values[i]))
                throw Error(src.path + ": voxel (" + coordText(voxelAt(spec.dims, z0, i)) + ") holds " + quoteValue(word) +
                            ", not a finite " + rawTypeName(spec.type) + " sample");
        }
    });
}

}  // namespace

// ---- conversion ------------------------------------------------------------

openvdb::FloatGrid::Ptr readVolumeSamples(const RawDataSource& src, const RawVolumeSpec& spec) {
    initVdb();
    const std::uint64_t needed = rawByteCount(spec);
    if (spec.gridName.empty()) throw Error("--grid: the grid name must not be empty");
    if (!std::isfinite(spec.background) || std::fabs(spec.background) > double(FLT_MAX))
        throw Error("--background: must be a finite number within float range");
    requireRegularFile(src.path, "raw volume");
    // A plain file's size is known up front: fail before reading anything.
    if (src.encoding == SampleEncoding::Raw) checkSourceSize(src, spec, needed);
    else checkPackedSize(src, spec, needed);
    const openvdb::math::Transform::Ptr transform = rawTransform(spec);

    openvdb::FloatGrid::Ptr grid;
    try {
        grid = src.encoding == SampleEncoding::Ascii ? readAscii(src, spec) : readBinary(src, spec);
    } catch (const bio::gzip_error& e) {
        throw Error(src.path + ": " + gzipProblem(e));
    } catch (const std::ios_base::failure& e) {
        throw Error(src.path + ": " + (src.encoding == SampleEncoding::Gzip ? "corrupt gzip data (" : "read error (") +
                    e.what() + ")");
    }
    grid->setName(spec.gridName);
    // A fog volume's background is zero by definition; CT's -1000 is not one.
    grid->setGridClass(spec.background == 0.0 ? openvdb::GRID_FOG_VOLUME : openvdb::GRID_UNKNOWN);
    grid->setTransform(transform);
    grid->setSaveFloatAsHalf(false);
    return grid;
}

openvdb::FloatGrid::Ptr readRawVolume(const std::string& path, const RawVolumeSpec& spec) {
    RawDataSource src;
    src.path = path;
    src.encoding = endsWithText(path, ".gz") ? SampleEncoding::Gzip : SampleEncoding::Raw;
    return readVolumeSamples(src, spec);
}

}  // namespace weft
