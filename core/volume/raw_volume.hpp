#pragma once
// Headerless dense volumes ("raw" files, as scanners and the classic volume
// data sets ship them): X*Y*Z samples, x fastest, then y, then z, optionally
// gzip-compressed. They become sparse float grids: values kept as numbers
// (u8 stays 0..255), zero samples inactive background.
#include <cstdint>
#include <string>

#include <openvdb/openvdb.h>

namespace weft {

enum class RawType { U8, U16, F32 };
enum class ByteOrder { Little, Big };

struct RawVolumeSpec {
    openvdb::Coord dims{0, 0, 0};  // samples along x, y, z
    RawType type = RawType::U8;
    ByteOrder byteOrder = ByteOrder::Little;  // of u16 and f32 samples
    openvdb::Vec3d spacing{1.0, 1.0, 1.0};    // world size of one voxel
    std::string gridName = "density";
};

// Largest accepted size along one axis, and of the whole file: beyond these
// the numbers are a typo, not a data set.
inline constexpr std::int64_t kMaxRawDim = std::int64_t(1) << 30;
inline constexpr std::uint64_t kMaxRawBytes = std::uint64_t(1) << 40;  // 1 TiB

// Option text parsers; errors name the option and the text.
openvdb::Coord parseRawDims(const std::string& text);      // "X,Y,Z", positive integers
openvdb::Vec3d parseRawSpacing(const std::string& text);   // "sx,sy,sz", positive finite numbers
RawType parseRawType(const std::string& text);             // u8|u16|f32
ByteOrder parseByteOrder(const std::string& text);         // little|big

const char* rawTypeName(RawType type);
std::size_t rawTypeBytes(RawType type);

// Bytes the file must hold; throws when the product overflows or is absurd.
std::uint64_t rawByteCount(const RawVolumeSpec& spec);

// "--dims 256,256,256 --type u8", how errors describe what was asked for.
std::string describeRawSpec(const RawVolumeSpec& spec);

// Reads PATH (gzip when it ends in ".gz") into a fog-volume float grid named
// spec.gridName with a linear transform of voxel size spec.spacing. Throws
// weft::Error when the file is missing, unreadable, corrupt, holds a
// different number of bytes than the spec needs, or holds non-finite floats.
openvdb::FloatGrid::Ptr readRawVolume(const std::string& path, const RawVolumeSpec& spec);

}  // namespace weft
