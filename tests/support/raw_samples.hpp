#pragma once
// Small raw volumes for the convert tests: a deterministic sample pattern
// with zeros sprinkled in, its encoding in each sample type and byte order,
// and a voxel-by-voxel comparison of a grid against it.
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <boost/iostreams/filter/gzip.hpp>
#include <boost/iostreams/filtering_stream.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/volume/raw_volume.hpp"

namespace weft::test {

inline std::size_t voxelIndex(const openvdb::Coord& dims, int x, int y, int z) {
    return std::size_t(x) + std::size_t(dims.x()) * (std::size_t(y) + std::size_t(dims.y()) * std::size_t(z));
}

// One value per voxel, x fastest. About a quarter are zero; the rest use
// the type's range (u16 values have two distinct bytes so a wrong byte
// order shows; f32 values are fractional and of both signs).
inline std::vector<float> samplePattern(const openvdb::Coord& dims, RawType type) {
    std::vector<float> v(std::size_t(dims.x()) * dims.y() * dims.z());
    for (int z = 0; z < dims.z(); ++z)
        for (int y = 0; y < dims.y(); ++y)
            for (int x = 0; x < dims.x(); ++x) {
                float& s = v[voxelIndex(dims, x, y, z)];
                if ((x + 2 * y + 3 * z) % 4 == 0) continue;
                switch (type) {
                    case RawType::U8: s = float(1 + (x * 7 + y * 13 + z * 29) % 255); break;
                    case RawType::U16: s = float(1 + (x * 4099 + y * 257 + z * 9973) % 65535); break;
                    case RawType::F32: s = (float(x) - 2.5f) * 0.37f + float(y) * 1.25f - float(z) * 0.001f; break;
                }
            }
    return v;
}

// The file bytes of `values` stored as `type` in byte order `order`.
inline std::string encodeSamples(const std::vector<float>& values, RawType type, ByteOrder order) {
    const std::size_t size = rawTypeBytes(type);
    const bool swap = (order == ByteOrder::Big) != (std::endian::native == std::endian::big);
    std::string bytes(values.size() * size, '\0');
    for (std::size_t i = 0; i < values.size(); ++i) {
        unsigned char word[4] = {};
        if (type == RawType::U8) word[0] = static_cast<unsigned char>(values[i]);
        if (type == RawType::U16) {
            const auto u = static_cast<std::uint16_t>(values[i]);
            std::memcpy(word, &u, 2);
        }
        if (type == RawType::F32) std::memcpy(word, &values[i], 4);
        for (std::size_t b = 0; b < size; ++b) bytes[i * size + b] = char(word[swap ? size - 1 - b : b]);
    }
    return bytes;
}

inline void writeBinary(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

inline void writeGzip(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream file(path, std::ios::binary);
    boost::iostreams::filtering_ostream out;
    out.push(boost::iostreams::gzip_compressor());
    out.push(file);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

// Every voxel of the box holds its sample, active exactly when non-zero,
// and nothing outside the box is active.
inline void expectGridHolds(const openvdb::FloatGrid& grid, const openvdb::Coord& dims, const std::vector<float>& values) {
    auto acc = grid.getConstAccessor();
    std::size_t mismatches = 0;
    openvdb::Index64 nonZero = 0;
    for (int z = 0; z < dims.z(); ++z)
        for (int y = 0; y < dims.y(); ++y)
            for (int x = 0; x < dims.x(); ++x) {
                const openvdb::Coord c(x, y, z);
                const float want = values[voxelIndex(dims, x, y, z)];
                nonZero += want != 0.0f;
                if (acc.getValue(c) == want && acc.isValueOn(c) == (want != 0.0f)) continue;
                if (++mismatches <= 5)
                    ADD_FAILURE() << "voxel " << c << ": got " << acc.getValue(c) << (acc.isValueOn(c) ? " (on)" : " (off)")
                                  << ", want " << want;
            }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_EQ(grid.activeVoxelCount(), nonZero);
    EXPECT_EQ(grid.background(), 0.0f);
    if (nonZero > 0) {
        const openvdb::CoordBBox box(openvdb::Coord(0), dims - openvdb::Coord(1));
        EXPECT_TRUE(box.isInside(grid.evalActiveVoxelBoundingBox()));
    }
}

}  // namespace weft::test
