// The text of convert's options, the names and sizes of the sample types,
// and the grid transform they describe.
#include <cfloat>
#include <cstdio>
#include <cmath>

#include "core/base/error.hpp"
#include "core/base/world_limit.hpp"
#include "core/volume/io/header_text.hpp"
#include "core/volume/io/raw_samples.hpp"

namespace weft {

namespace {

std::string coordText(const openvdb::math::Coord& c) {
    return std::to_string(c.x()) + "," + std::to_string(c.y()) + "," + std::to_string(c.z());
}

// n comma-separated finite numbers, or nothing.
bool parseNumbers(const std::string& text, std::size_t n, double* out) {
    const std::vector<std::string> parts = splitOn(text, ',');
    if (parts.size() != n) return false;
    for (std::size_t i = 0; i < n; ++i)
        if (!parseFinite(parts[i], out[i])) return false;
    return true;
}

struct TypeName {
    RawType type;
    const char* name;
    std::size_t bytes;
};

constexpr TypeName kTypes[] = {{RawType::U8, "u8", 1},  {RawType::I8, "i8", 1},   {RawType::U16, "u16", 2},
                               {RawType::I16, "i16", 2}, {RawType::U32, "u32", 4}, {RawType::I32, "i32", 4},
                               {RawType::F32, "f32", 4}, {RawType::F64, "f64", 8}};

bool isIdentity(const openvdb::math::Mat3d& m) {
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (m(r, c) != (r == c ? 1.0 : 0.0)) return false;
    return true;
}

openvdb::math::Transform::Ptr spacingTransform(const openvdb::math::Vec3d& s) {
    if (s.x() == s.y() && s.y() == s.z()) return openvdb::math::Transform::createLinearTransform(s.x());
    return std::make_shared<openvdb::math::Transform>(std::make_shared<openvdb::math::ScaleMap>(s));
}

}  // namespace

openvdb::math::Coord parseRawDims(const std::string& text) {
    const std::vector<std::string> parts = splitOn(text, ',');
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
    return openvdb::math::Coord(int(d[0]), int(d[1]), int(d[2]));
}

openvdb::math::Vec3d parseRawSpacing(const std::string& text) {
    openvdb::math::Vec3d s;
    if (!parseNumbers(text, 3, s.asPointer()) || !(s.x() > 0 && s.y() > 0 && s.z() > 0))
        throw Error("--spacing '" + text + "': expected 3 positive numbers sx,sy,sz (e.g. 1,1,2.5)");
    return s;
}

openvdb::math::Vec3d parseRawOrigin(const std::string& text) {
    openvdb::math::Vec3d o;
    if (!parseNumbers(text, 3, o.asPointer()))
        throw Error("--origin '" + text + "': expected 3 finite numbers x,y,z (e.g. -120,-120,40.5)");
    return o;
}

openvdb::math::Mat3d parseRawDirection(const std::string& text) {
    double v[9];
    if (!parseNumbers(text, 9, v))
        throw Error("--direction '" + text + "': expected 9 finite numbers, the 3x3 matrix row by row (e.g. 1,0,0,0,1,0,0,0,1)");
    const openvdb::math::Mat3d m(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]);
    checkDirection(m, "--direction '" + text + "'");
    return m;
}

double parseRawBackground(const std::string& text) {
    double v;
    if (!parseFinite(text, v) || std::fabs(v) > double(FLT_MAX))
        throw Error("--background '" + text + "': expected a finite number within float range (e.g. 0 or -1000)");
    return v;
}

void checkDirection(const openvdb::math::Mat3d& m, const std::string& what) {
    double lengths = 1.0;
    for (int c = 0; c < 3; ++c) {
        const openvdb::math::Vec3d column(m(0, c), m(1, c), m(2, c));
        if (!std::isfinite(column.x()) || !std::isfinite(column.y()) || !std::isfinite(column.z()))
            throw Error(what + ": the direction matrix must hold finite numbers");
        lengths *= column.length();
    }
    // |det| <= product of column lengths, with equality for orthogonal
    // columns: a tiny ratio means the axes (nearly) lie in one plane.
    const double det = m.det();
    if (!(lengths > 0) || !std::isfinite(det) || std::fabs(det) <= 1e-9 * lengths)
        throw Error(what + ": the direction matrix is singular (determinant " + std::to_string(det) +
                    "); its columns must span 3-D space");
}

RawType parseRawType(const std::string& text) {
    for (const TypeName& t : kTypes)
        if (text == t.name) return t.type;
    throw Error("--type '" + text + "': unknown sample type (expected " + rawTypeNames() + ")");
}

ByteOrder parseByteOrder(const std::string& text) {
    if (text == "little") return ByteOrder::Little;
    if (text == "big") return ByteOrder::Big;
    throw Error("--endian '" + text + "': unknown byte order (expected little|big)");
}

const char* rawTypeName(RawType type) {
    for (const TypeName& t : kTypes)
        if (t.type == type) return t.name;
    return "?";
}

const char* rawTypeNames() { return "u8|i8|u16|i16|u32|i32|f32|f64"; }

std::size_t rawTypeBytes(RawType type) {
    for (const TypeName& t : kTypes)
        if (t.type == type) return t.bytes;
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

// Within the ranges a volume may be placed in (core/base/world_limit.hpp):
// OpenVDB's own ArithmeticError text reached the user for a spacing of 1e-30.
void checkPlacement(const RawVolumeSpec& spec) {
    char text[200];
    for (int i = 0; i < 3; ++i)
        if (!(spec.spacing[i] >= kMinVoxelSize && spec.spacing[i] <= kMaxVoxelSize)) {
            std::snprintf(text, sizeof text, "voxel spacing %g,%g,%g is outside [%g, %g] on some axis", spec.spacing.x(), spec.spacing.y(),
                          spec.spacing.z(), kMinVoxelSize, kMaxVoxelSize);
            throw Error(describeRawSpec(spec) + ": " + text);
        }
    for (int i = 0; i < 3; ++i)
        if (!(std::abs(spec.origin[i]) <= kWorldLimit)) {
            std::snprintf(text, sizeof text, "origin %g,%g,%g lies beyond the +-%g units weft renders in", spec.origin.x(), spec.origin.y(),
                          spec.origin.z(), kWorldLimit);
            throw Error(describeRawSpec(spec) + ": " + text);
        }
}

openvdb::math::Transform::Ptr rawTransform(const RawVolumeSpec& spec) {
    checkPlacement(spec);
    if (isIdentity(spec.direction)) {
        auto transform = spacingTransform(spec.spacing);
        if (spec.origin != openvdb::math::Vec3d(0.0)) transform->postTranslate(spec.origin);
        return transform;
    }
    checkDirection(spec.direction, "the grid transform");
    // OpenVDB maps row vectors: world = index * M, so M's upper 3x3 is the
    // transpose of direction * diag(spacing) and its last row the origin.
    openvdb::Mat4d m = openvdb::Mat4d::identity();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m(c, r) = spec.direction(r, c) * spec.spacing[c];
    for (int r = 0; r < 3; ++r) m(3, r) = spec.origin[r];
    return openvdb::math::Transform::createLinearTransform(m);
}

}  // namespace weft
