#pragma once
// Small raw volumes for the convert tests: a deterministic sample pattern
// with zeros sprinkled in and each type's extremes, its encoding in each
// sample type and byte order, and a voxel-by-voxel comparison of a grid
// against it.
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <boost/iostreams/device/back_inserter.hpp>
#include <boost/iostreams/filter/gzip.hpp>
#include <boost/iostreams/filtering_stream.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/volume/io/raw_volume.hpp"

namespace weft::test {

inline std::size_t voxelIndex(const openvdb::Coord& dims, int x, int y, int z) {
    return std::size_t(x) + std::size_t(dims.x()) * (std::size_t(y) + std::size_t(dims.y()) * std::size_t(z));
}

inline constexpr RawType kAllRawTypes[] = {RawType::U8,  RawType::I8,  RawType::U16, RawType::I16,
                                           RawType::U32, RawType::I32, RawType::F32, RawType::F64};

// The smallest and largest sample of the type a float grid holds (f64: the
// float range).
inline std::pair<double, double> typeExtremes(RawType type) {
    switch (type) {
        case RawType::U8: return {0, 255};
        case RawType::I8: return {-128, 127};
        case RawType::U16: return {0, 65535};
        case RawType::I16: return {-32768, 32767};
        case RawType::U32: return {0, 4294967295.0};
        case RawType::I32: return {-2147483648.0, 2147483647.0};
        case RawType::F32: return {-double(std::numeric_limits<float>::max()), double(std::numeric_limits<float>::max())};
        case RawType::F64: return {-double(std::numeric_limits<float>::max()), double(std::numeric_limits<float>::max())};
    }
    return {0, 0};
}

// One exact value of the type per voxel, x fastest. About a quarter are
// zero; the rest use the type's range (multi-byte values have distinct bytes
// so a wrong byte order shows; signed values are of both signs; floats are
// fractional, f64 ones finer than a float). The last two voxels hold the
// type's minimum and maximum.
inline std::vector<double> samplePattern(const openvdb::Coord& dims, RawType type) {
    std::vector<double> v(std::size_t(dims.x()) * dims.y() * dims.z());
    for (int z = 0; z < dims.z(); ++z)
        for (int y = 0; y < dims.y(); ++y)
            for (int x = 0; x < dims.x(); ++x) {
                double& s = v[voxelIndex(dims, x, y, z)];
                if ((x + 2 * y + 3 * z) % 4 == 0) continue;
                const std::uint64_t h = std::uint64_t(x) * 2654435761u + std::uint64_t(y) * 40503u + std::uint64_t(z) * 9973u;
                switch (type) {
                    case RawType::U8: s = double(1 + (x * 7 + y * 13 + z * 29) % 255); break;
                    case RawType::I8: s = double(int((x * 7 + y * 13 + z * 29) % 256) - 128); break;
                    case RawType::U16: s = double(1 + (x * 4099 + y * 257 + z * 9973) % 65535); break;
                    case RawType::I16: s = double(int((x * 4099 + y * 257 + z * 9973) % 65536) - 32768); break;
                    case RawType::U32: s = double(h % 4294967296u); break;
                    case RawType::I32: s = double(std::int64_t(h % 4294967296u) - 2147483648LL); break;
                    case RawType::F32: s = double((float(x) - 2.5f) * 0.37f + float(y) * 1.25f - float(z) * 0.001f); break;
                    case RawType::F64: s = (double(x) - 2.5) * 0.37e20 + double(y) * 1.25 - double(z) * 1e-9; break;
                }
            }
    const auto [lo, hi] = typeExtremes(type);
    if (v.size() > 2) v[v.size() - 2] = lo, v[v.size() - 1] = hi;
    return v;
}

template <class T>
void storeAs(double value, unsigned char* word) {
    const T t = static_cast<T>(value);
    std::memcpy(word, &t, sizeof(T));
}

// The file bytes of `values` stored as `type` in byte order `order`.
template <class V>
std::string encodeSamples(const std::vector<V>& values, RawType type, ByteOrder order) {
    const std::size_t size = rawTypeBytes(type);
    const bool swap = (order == ByteOrder::Big) != (std::endian::native == std::endian::big);
    std::string bytes(values.size() * size, '\0');
    for (std::size_t i = 0; i < values.size(); ++i) {
        unsigned char word[8] = {};
        const double v = double(values[i]);
        switch (type) {
            case RawType::U8: storeAs<std::uint8_t>(v, word); break;
            case RawType::I8: storeAs<std::int8_t>(v, word); break;
            case RawType::U16: storeAs<std::uint16_t>(v, word); break;
            case RawType::I16: storeAs<std::int16_t>(v, word); break;
            case RawType::U32: storeAs<std::uint32_t>(v, word); break;
            case RawType::I32: storeAs<std::int32_t>(v, word); break;
            case RawType::F32: storeAs<float>(v, word); break;
            case RawType::F64: storeAs<double>(v, word); break;
        }
        for (std::size_t b = 0; b < size; ++b) bytes[i * size + b] = char(word[swap ? size - 1 - b : b]);
    }
    return bytes;
}

inline void writeBinary(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

inline std::string gzipBytes(const std::string& bytes) {
    std::string out;
    {
        boost::iostreams::filtering_ostream z;
        z.push(boost::iostreams::gzip_compressor());
        z.push(boost::iostreams::back_inserter(out));
        z.write(bytes.data(), std::streamsize(bytes.size()));
    }
    return out;
}

inline void writeGzip(const std::filesystem::path& path, const std::string& bytes) { writeBinary(path, gzipBytes(bytes)); }

// Every voxel of the box holds float(its sample), active exactly when that
// differs from the background, and nothing outside the box is active.
template <class V>
void expectGridHolds(const openvdb::FloatGrid& grid, const openvdb::Coord& dims, const std::vector<V>& values,
                     float background = 0.0f) {
    auto acc = grid.getConstAccessor();
    std::size_t mismatches = 0;
    openvdb::Index64 active = 0;
    for (int z = 0; z < dims.z(); ++z)
        for (int y = 0; y < dims.y(); ++y)
            for (int x = 0; x < dims.x(); ++x) {
                const openvdb::Coord c(x, y, z);
                const float want = float(values[voxelIndex(dims, x, y, z)]);
                active += want != background;
                if (acc.getValue(c) == want && acc.isValueOn(c) == (want != background)) continue;
                if (++mismatches <= 5)
                    ADD_FAILURE() << "voxel " << c << ": got " << acc.getValue(c) << (acc.isValueOn(c) ? " (on)" : " (off)")
                                  << ", want " << want;
            }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_EQ(grid.activeVoxelCount(), active);
    EXPECT_EQ(grid.background(), background);
    if (active > 0) {
        const openvdb::CoordBBox box(openvdb::Coord(0), dims - openvdb::Coord(1));
        EXPECT_TRUE(box.isInside(grid.evalActiveVoxelBoundingBox()));
    }
}

}  // namespace weft::test
