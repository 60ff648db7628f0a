#pragma once
// Dense volumes as scanners and the classic volume data sets ship them:
// X*Y*Z samples, x fastest, then y, then z, either headerless ("raw" files,
// optionally gzip-compressed) or after a header (NRRD, NumPy, VTK; see
// volume_import.hpp). They become sparse float grids (raw_samples.hpp reads
// them): values kept as numbers (u8 stays 0..255, Hounsfield units stay
// -1000 for air), samples equal to the background value inactive. This
// header describes them with OpenVDB's math types only, so the header
// parsers compile without OpenVDB's grids.
#include <cstdint>
#include <string>

#include <openvdb/math/Coord.h>
#include <openvdb/math/Mat3.h>
#include <openvdb/math/Vec3.h>

namespace weft {

enum class RawType { U8, I8, U16, I16, U32, I32, F32, F64 };
enum class ByteOrder { Little, Big };
// How the samples are stored: binary words, one gzip stream of binary
// words, or whitespace-separated decimal numbers.
enum class SampleEncoding { Raw, Gzip, Ascii };

struct RawVolumeSpec {
    openvdb::math::Coord dims{0, 0, 0};  // samples along x, y, z
    RawType type = RawType::U8;
    ByteOrder byteOrder = ByteOrder::Little;  // of multi-byte samples
    openvdb::math::Vec3d spacing{1.0, 1.0, 1.0};    // world size of one voxel
    openvdb::math::Vec3d origin{0.0, 0.0, 0.0};     // world position of voxel (0,0,0)
    // Columns: the world directions of the index x, y and z axes, so that
    // world = origin + direction * diag(spacing) * (i, j, k).
    openvdb::math::Mat3d direction = openvdb::math::Mat3d::identity();
    // Samples equal to it (after conversion to float) are inactive, and it
    // is the grid's background: 0 for densities, e.g. -1000 (air) for CT.
    double background = 0.0;
    std::string gridName = "density";
};

// Where the samples lie: a file, the bytes before them (a header), how they
// are encoded, and what the messages call the description they must match.
struct RawDataSource {
    std::string path;
    std::uint64_t offset = 0;       // bytes of the file before the samples
    SampleEncoding encoding = SampleEncoding::Raw;
    std::uint64_t skipDecoded = 0;  // bytes of the decompressed stream before the samples
    bool trailingAllowed = false;   // bytes after the samples belong to something else
    std::string describedBy;        // "--dims 5,4,3 --type u8" when empty
};

// Largest accepted size along one axis, and of the whole file: beyond these
// the numbers are a typo, not a data set.
inline constexpr std::int64_t kMaxRawDim = std::int64_t(1) << 30;
inline constexpr std::uint64_t kMaxRawBytes = std::uint64_t(1) << 40;  // 1 TiB

// Option text parsers; errors name the option and the text.
openvdb::math::Coord parseRawDims(const std::string& text);        // "X,Y,Z", positive integers
openvdb::math::Vec3d parseRawSpacing(const std::string& text);     // "sx,sy,sz", positive finite numbers
openvdb::math::Vec3d parseRawOrigin(const std::string& text);      // "x,y,z", finite numbers
openvdb::math::Mat3d parseRawDirection(const std::string& text);   // 9 finite numbers, row-major, not singular
double parseRawBackground(const std::string& text);          // a finite number within float range
RawType parseRawType(const std::string& text);               // u8|i8|u16|i16|u32|i32|f32|f64
ByteOrder parseByteOrder(const std::string& text);           // little|big

const char* rawTypeName(RawType type);
const char* rawTypeNames();  // "u8|i8|u16|i16|u32|i32|f32|f64"
std::size_t rawTypeBytes(RawType type);

// Throws "<what>: ..." unless every entry is finite and the matrix is far
// from singular (its determinant against the product of its column lengths).
void checkDirection(const openvdb::math::Mat3d& direction, const std::string& what);

// Bytes the samples take; throws when the product overflows or is absurd.
std::uint64_t rawByteCount(const RawVolumeSpec& spec);

// "--dims 256,256,256 --type u8", how errors describe what was asked for.
std::string describeRawSpec(const RawVolumeSpec& spec);

}  // namespace weft
