#pragma once
// Fuzz target: headerless raw volumes (core/volume/io/raw_volume.cpp), as
// `weft convert` reads them. The first bytes of the input choose the spec
// the way a command line would give it, through the option parsers:
//   byte 0: sample type (an index into the type names)  byte 1: byte order
//   byte 2: gzip (odd) or plain                          bytes 3, 4: X, Y (1..32)
//   byte 5: Z for gzip data (1..32); plain data takes Z from its length, so
//   most inputs reach the decoder rather than the size check.
// The rest is the file.
#include <algorithm>
#include <cmath>

#include "core/volume/io/raw_samples.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace weft::fuzz {

// Names the option parser accepts, plus one it must refuse. Types added to
// core/volume/io/raw_volume.hpp belong here too.
inline constexpr const char* kRawTypeNames[] = {"u8", "u16", "f32", "i8", "i16", "i32", "u32", "f64", "x"};

inline Outcome rawVolume(const std::uint8_t* data, std::size_t size) {
    constexpr std::size_t kHeader = 6;
    if (size < kHeader) return {false, "", true};
    const std::string_view payload = asText(data + kHeader, size - kHeader);
    return guarded([&] {
        RawVolumeSpec spec;
        spec.type = parseRawType(kRawTypeNames[data[0] % std::size(kRawTypeNames)]);
        spec.byteOrder = parseByteOrder(data[1] % 2 ? "big" : "little");
        const bool gzip = data[2] % 2;
        const int nx = 1 + data[3] % 32, ny = 1 + data[4] % 32;
        const std::size_t slice = std::size_t(nx) * ny * rawTypeBytes(spec.type);
        const int nz = gzip ? 1 + data[5] % 32 : int(std::max<std::size_t>(1, payload.size() / slice));
        spec.dims = parseRawDims(std::to_string(nx) + "," + std::to_string(ny) + "," + std::to_string(nz));
        const std::string path = writeScratch(gzip ? "volume.raw.gz" : "volume.raw", payload);
        const openvdb::FloatGrid::Ptr grid = readRawVolume(path, spec);
        for (auto it = grid->cbeginValueOn(); it; ++it) require(std::isfinite(*it), "finite voxel values");
        const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
        require(grid->activeVoxelCount() == 0 || (box.min().x() >= 0 && box.max().x() < nx && box.max().y() < ny && box.max().z() < nz),
                "active voxels inside the dims");
    });
}

}  // namespace weft::fuzz
