#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/base/error.hpp"
#include "core/volume/io/raw_samples.hpp"
#include "tests/support/raw_samples.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;
using namespace weft::test;
using openvdb::Coord;

namespace {


RawVolumeSpec specOf(Coord dims, RawType type, ByteOrder order = ByteOrder::Little) {
    RawVolumeSpec spec;
    spec.dims = dims;
    spec.type = type;
    spec.byteOrder = order;
    return spec;
}

// Writes the pattern in the spec's encoding, reads it back, compares.
void expectRoundTrip(const RawVolumeSpec& spec, bool gzip) {
    TempDir dir;
    const std::vector<double> values = samplePattern(spec.dims, spec.type);
    const std::string bytes = encodeSamples(values, spec.type, spec.byteOrder);
    const auto path = dir / (gzip ? "v.raw.gz" : "v.raw");
    gzip ? writeGzip(path, bytes) : writeBinary(path, bytes);
    const openvdb::FloatGrid::Ptr grid = readRawVolume(path.string(), spec);
    expectGridHolds(*grid, spec.dims, values);
}

}  // namespace

TEST(RawVolumeOptions, DimsAcceptThreePositiveIntegers) {
    EXPECT_EQ(parseRawDims("256,128,3"), Coord(256, 128, 3));
    EXPECT_EQ(parseRawDims("1,1,1"), Coord(1, 1, 1));
    EXPECT_EQ(parseRawDims("1073741824,1,1"), Coord(1073741824, 1, 1));
}

TEST(RawVolumeOptions, DimsRejectAnythingElse) {
    for (const char* text : {"", "256", "256,256", "1,2,3,4", "0,1,1", "1,-2,1", "a,b,c", "1.5,2,3", " 1,2,3", "1,,3",
                             "+1,2,3", "0x10,2,3", "1,2,3,"}) {
        const std::string msg = errorOf([&] { parseRawDims(text); });
        EXPECT_NE(msg.find("expected 3 positive integers"), std::string::npos) << "'" << text << "': " << msg;
        EXPECT_NE(msg.find("--dims '" + std::string(text) + "'"), std::string::npos) << msg;
    }
}

TEST(RawVolumeOptions, DimsRejectAbsurdAxes) {
    for (const char* text : {"1073741825,1,1", "1,5000000000,1", "1,1,99999999999999999999999999"}) {
        const std::string msg = errorOf([&] { parseRawDims(text); });
        EXPECT_NE(msg.find("more than weft accepts"), std::string::npos) << text << ": " << msg;
    }
}

TEST(RawVolumeOptions, SpacingAcceptsPositiveNumbers) {
    EXPECT_EQ(parseRawSpacing("1,1,1"), openvdb::Vec3d(1, 1, 1));
    EXPECT_EQ(parseRawSpacing("0.5,2,1e-3"), openvdb::Vec3d(0.5, 2, 1e-3));
}

TEST(RawVolumeOptions, SpacingRejectsAnythingElse) {
    for (const char* text : {"", "1", "1,1", "1,1,1,1", "0,1,1", "1,-1,1", "nan,1,1", "1,inf,1", "x,1,1", "1,1,1mm"}) {
        const std::string msg = errorOf([&] { parseRawSpacing(text); });
        EXPECT_NE(msg.find("expected 3 positive numbers"), std::string::npos) << "'" << text << "': " << msg;
    }
}

TEST(RawVolumeOptions, TypeAndByteOrderNames) {
    EXPECT_EQ(parseRawType("u8"), RawType::U8);
    EXPECT_EQ(parseRawType("u16"), RawType::U16);
    EXPECT_EQ(parseRawType("f32"), RawType::F32);
    EXPECT_EQ(parseByteOrder("little"), ByteOrder::Little);
    EXPECT_EQ(parseByteOrder("big"), ByteOrder::Big);
    EXPECT_EQ(parseRawType("i8"), RawType::I8);
    EXPECT_EQ(parseRawType("i16"), RawType::I16);
    EXPECT_EQ(parseRawType("u32"), RawType::U32);
    EXPECT_EQ(parseRawType("i32"), RawType::I32);
    EXPECT_EQ(parseRawType("f64"), RawType::F64);
    for (RawType t : kAllRawTypes) EXPECT_EQ(parseRawType(rawTypeName(t)), t);
    EXPECT_NE(errorOf([] { parseRawType("u64"); })
                  .find("--type 'u64': unknown sample type (expected u8|i8|u16|i16|u32|i32|f32|f64)"),
              std::string::npos);
    EXPECT_NE(errorOf([] { parseByteOrder("middle"); }).find("expected little|big"), std::string::npos);
}

TEST(RawVolumeOptions, ByteCountAndItsLimits) {
    EXPECT_EQ(rawByteCount(specOf(Coord(256, 256, 256), RawType::U8)), 16777216u);
    EXPECT_EQ(rawByteCount(specOf(Coord(3, 5, 7), RawType::F32)), 420u);
    const int big = int(kMaxRawDim);
    EXPECT_NE(errorOf([&] { rawByteCount(specOf(Coord(big, big, big), RawType::U8)); }).find("overflows 64 bits"),
              std::string::npos);
    const std::string msg = errorOf([&] { rawByteCount(specOf(Coord(big, big, 2), RawType::U8)); });
    EXPECT_NE(msg.find("needs 2305843009213693952 bytes, more than the 1 TiB weft accepts"), std::string::npos) << msg;
}

TEST(RawVolume, RoundTripU8) { expectRoundTrip(specOf(Coord(5, 4, 3), RawType::U8), false); }
TEST(RawVolume, RoundTripU16LittleEndian) { expectRoundTrip(specOf(Coord(11, 9, 13), RawType::U16), false); }
TEST(RawVolume, RoundTripU16BigEndian) { expectRoundTrip(specOf(Coord(11, 9, 13), RawType::U16, ByteOrder::Big), false); }
TEST(RawVolume, RoundTripF32BothEndians) {
    expectRoundTrip(specOf(Coord(17, 3, 9), RawType::F32), false);
    expectRoundTrip(specOf(Coord(17, 3, 9), RawType::F32, ByteOrder::Big), false);
}
TEST(RawVolume, RoundTripGzip) {
    expectRoundTrip(specOf(Coord(21, 19, 18), RawType::U8), true);
    expectRoundTrip(specOf(Coord(21, 19, 18), RawType::U16, ByteOrder::Big), true);
}

// Slices wide enough that the volume is converted in several slabs, with
// partial leaf nodes at every far face.
TEST(RawVolume, RoundTripAcrossSlabs) { expectRoundTrip(specOf(Coord(1027, 1030, 19), RawType::U8), false); }

TEST(RawVolume, WrongByteOrderChangesValues) {
    TempDir dir;
    const RawVolumeSpec big = specOf(Coord(4, 4, 4), RawType::U16, ByteOrder::Big);
    const std::vector<double> values = samplePattern(big.dims, big.type);
    writeBinary(dir / "v.raw", encodeSamples(values, big.type, big.byteOrder));
    const auto grid = readRawVolume((dir / "v.raw").string(), specOf(big.dims, big.type, ByteOrder::Little));
    const float first = values[voxelIndex(big.dims, 1, 0, 0)];
    ASSERT_NE(first, 0.0f);
    EXPECT_NE(grid->tree().getValue(Coord(1, 0, 0)), first);
}

TEST(RawVolume, GridIsAFloatFogVolumeWithTheSpacing) {
    TempDir dir;
    RawVolumeSpec spec = specOf(Coord(2, 2, 2), RawType::U8);
    spec.spacing = openvdb::Vec3d(0.5, 2, 3);
    spec.gridName = "ct";
    writeBinary(dir / "v.raw", std::string("\1\2\3\4\0\0\0\7", 8));
    const auto grid = readRawVolume((dir / "v.raw").string(), spec);
    EXPECT_EQ(grid->getName(), "ct");
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_FALSE(grid->saveFloatAsHalf());
    EXPECT_TRUE(grid->transform().isLinear());
    EXPECT_TRUE(grid->transform().voxelSize().eq(openvdb::Vec3d(0.5, 2, 3)));
    EXPECT_TRUE(grid->transform().indexToWorld(Coord(1, 1, 1)).eq(openvdb::Vec3d(0.5, 2, 3)));
    EXPECT_EQ(grid->activeVoxelCount(), 5u);
    EXPECT_EQ(grid->tree().getValue(Coord(1, 1, 1)), 7.0f);
}

TEST(RawVolume, SizeMismatchNamesBothNumbers) {
    TempDir dir;
    writeBinary(dir / "v.raw", std::string(59, '\1'));
    const std::string path = (dir / "v.raw").string();
    EXPECT_EQ(errorOf([&] { readRawVolume(path, specOf(Coord(5, 4, 3), RawType::U8)); }),
              path + ": holds 59 bytes but --dims 5,4,3 --type u8 needs 60");
    writeGzip(dir / "v.raw.gz", std::string(61, '\1'));
    EXPECT_EQ(errorOf([&] { readRawVolume(path + ".gz", specOf(Coord(5, 4, 3), RawType::U8)); }),
              path + ".gz: unpacks to 61 bytes but --dims 5,4,3 --type u8 needs 60");
    writeGzip(dir / "v.raw.gz", std::string(119, '\1'));
    EXPECT_EQ(errorOf([&] { readRawVolume(path + ".gz", specOf(Coord(5, 4, 3), RawType::U16)); }),
              path + ".gz: unpacks to 119 bytes but --dims 5,4,3 --type u16 needs 120");
}

TEST(RawVolume, NonFiniteFloatsAreRejectedWithTheirVoxel) {
    TempDir dir;
    std::vector<float> values(8, 1.0f);
    values[voxelIndex(Coord(2, 2, 2), 1, 0, 1)] = std::numeric_limits<float>::quiet_NaN();
    writeBinary(dir / "v.raw", encodeSamples(values, RawType::F32, ByteOrder::Little));
    const std::string msg = errorOf([&] { readRawVolume((dir / "v.raw").string(), specOf(Coord(2, 2, 2), RawType::F32)); });
    EXPECT_NE(msg.find("voxel (1,0,1)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("must be finite"), std::string::npos) << msg;
}

TEST(RawVolume, MissingFileAndCorruptGzip) {
    TempDir dir;
    const std::string missing = (dir / "none.raw").string();
    EXPECT_EQ(errorOf([&] { readRawVolume(missing, specOf(Coord(1, 1, 1), RawType::U8)); }), "raw volume '" + missing + "': no such file");
    writeBinary(dir / "plain.raw.gz", std::string(8, '\1'));
    EXPECT_NE(errorOf([&] { readRawVolume((dir / "plain.raw.gz").string(), specOf(Coord(2, 2, 2), RawType::U8)); })
                  .find("not gzip data"),
              std::string::npos);
}

// ---- signed and wide types -------------------------------------------------

TEST(RawVolume, EveryTypeRoundTripsExactlyInBothByteOrders) {
    for (RawType type : kAllRawTypes)
        for (ByteOrder order : {ByteOrder::Little, ByteOrder::Big}) {
            SCOPED_TRACE(std::string(rawTypeName(type)) + (order == ByteOrder::Big ? " big" : " little"));
            expectRoundTrip(specOf(Coord(13, 6, 5), type, order), false);
        }
}

TEST(RawVolume, EveryTypeRoundTripsThroughGzip) {
    for (RawType type : kAllRawTypes) {
        SCOPED_TRACE(rawTypeName(type));
        expectRoundTrip(specOf(Coord(9, 8, 7), type, ByteOrder::Big), true);
    }
}

// The values CT and simulations store, read back as the numbers they are.
TEST(RawVolume, ExtremesAndNegativesKeepTheirValues) {
    TempDir dir;
    struct Case {
        RawType type;
        std::vector<double> values;
    };
    const std::vector<Case> cases = {
        {RawType::I8, {-128, 127, -1, 0, 1, -100, 100, 5}},
        {RawType::I16, {-32768, 32767, -1000, 0, 3071, -1, 1, -1024}},
        {RawType::U16, {0, 65535, 1, 256, 255, 4096, 65534, 2}},
        {RawType::I32, {-2147483648.0, 2147483647.0, -16777216, 16777216, -1, 0, 7, -7}},
        {RawType::U32, {0, 4294967295.0, 16777216, 1, 2, 3, 4, 5}},
        {RawType::F64, {-3.0e38, 3.0e38, 1e-30, -0.1, 0, -1e-37, 123456.789012345, -2.5}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(rawTypeName(c.type));
        const RawVolumeSpec spec = specOf(Coord(2, 2, 2), c.type, ByteOrder::Little);
        writeBinary(dir / "v.raw", encodeSamples(c.values, c.type, ByteOrder::Little));
        const auto grid = readRawVolume((dir / "v.raw").string(), spec);
        expectGridHolds(*grid, spec.dims, c.values);
    }
    // The samples are numbers: -1000 (air) is -1000, INT16_MIN is -32768.
    writeBinary(dir / "ct.raw", encodeSamples(std::vector<double>{-1000, -32768, 0, 40, 0, 0, 0, 0}, RawType::I16, ByteOrder::Big));
    const auto ct = readRawVolume((dir / "ct.raw").string(), specOf(Coord(2, 2, 2), RawType::I16, ByteOrder::Big));
    EXPECT_EQ(ct->tree().getValue(Coord(0, 0, 0)), -1000.0f);
    EXPECT_EQ(ct->tree().getValue(Coord(1, 0, 0)), -32768.0f);
    EXPECT_EQ(ct->tree().getValue(Coord(1, 1, 0)), 40.0f);
}

// Integers beyond 2^24 become the nearest float: the documented rounding.
TEST(RawVolume, WideIntegersRoundToTheNearestFloat) {
    TempDir dir;
    const std::vector<double> values = {16777217, 2147483647.0, 4294967295.0, 1, 1, 1, 1, 1};
    writeBinary(dir / "v.raw", encodeSamples(values, RawType::U32, ByteOrder::Little));
    const auto grid = readRawVolume((dir / "v.raw").string(), specOf(Coord(2, 2, 2), RawType::U32));
    EXPECT_EQ(grid->tree().getValue(Coord(0, 0, 0)), 16777216.0f);
    EXPECT_EQ(grid->tree().getValue(Coord(1, 0, 0)), 2147483648.0f);
    EXPECT_EQ(grid->tree().getValue(Coord(0, 1, 0)), 4294967296.0f);
}

TEST(RawVolume, DoublesBeyondFloatRangeAreRejectedWithTheirVoxel) {
    TempDir dir;
    for (const double bad : {1e39, -1e300, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
        std::vector<double> values(8, 2.0);
        values[voxelIndex(Coord(2, 2, 2), 0, 1, 1)] = bad;
        writeBinary(dir / "v.raw", encodeSamples(values, RawType::F64, ByteOrder::Big));
        const std::string msg =
            errorOf([&] { readRawVolume((dir / "v.raw").string(), specOf(Coord(2, 2, 2), RawType::F64, ByteOrder::Big)); });
        EXPECT_NE(msg.find("voxel (0,1,1) holds"), std::string::npos) << msg;
        const bool finite = std::isfinite(bad);
        EXPECT_NE(msg.find(finite ? "beyond float range" : "must be finite"), std::string::npos) << msg;
    }
}

// ---- background ------------------------------------------------------------

TEST(RawVolume, BackgroundValueIsInactiveAndTheGridsBackground) {
    TempDir dir;
    RawVolumeSpec spec = specOf(Coord(4, 4, 4), RawType::I16);
    spec.background = -1000;
    std::vector<double> values(64, -1000.0);
    values[voxelIndex(spec.dims, 1, 2, 3)] = 0;  // water: a value like any other
    values[voxelIndex(spec.dims, 3, 3, 3)] = 1200;
    writeBinary(dir / "v.raw", encodeSamples(values, spec.type, spec.byteOrder));
    const auto grid = readRawVolume((dir / "v.raw").string(), spec);
    expectGridHolds(*grid, spec.dims, values, -1000.0f);
    EXPECT_EQ(grid->activeVoxelCount(), 2u);
    EXPECT_TRUE(grid->tree().isValueOn(Coord(1, 2, 3)));
    EXPECT_EQ(grid->tree().getValue(Coord(1, 2, 3)), 0.0f);
    EXPECT_EQ(grid->tree().getValue(Coord(100, 0, 0)), -1000.0f);  // outside: the background
    EXPECT_NE(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
}

TEST(RawVolumeOptions, OriginDirectionAndBackgroundText) {
    EXPECT_EQ(parseRawOrigin("-120,0.5,1e3"), openvdb::Vec3d(-120, 0.5, 1000));
    const openvdb::Mat3d m = parseRawDirection("0,-1,0,1,0,0,0,0,1");
    EXPECT_EQ(m(0, 1), -1.0);
    EXPECT_EQ(m(1, 0), 1.0);
    EXPECT_EQ(parseRawBackground("-1000"), -1000.0);
    for (const char* text : {"", "1,2", "1,2,3,4", "nan,0,0", "1,inf,0", "a,b,c"})
        EXPECT_NE(errorOf([&] { parseRawOrigin(text); }).find("--origin '" + std::string(text) + "': expected 3 finite numbers"),
                  std::string::npos)
            << text;
    for (const char* text : {"", "1,0,0,0,1,0,0,0", "1,0,0,0,1,0,0,0,1,0", "1,0,0,0,nan,0,0,0,1", "1,0,0,0,1,0,0,0,inf"})
        EXPECT_NE(errorOf([&] { parseRawDirection(text); }).find("--direction '" + std::string(text) + "': expected 9 finite numbers"),
                  std::string::npos)
            << text;
    for (const char* text : {"0,0,0,0,0,0,0,0,0", "1,0,0,0,1,0,0,0,0", "1,2,3,2,4,6,0,0,1", "1,1,0,1,1,1e-12,0,0,1"})
        EXPECT_NE(errorOf([&] { parseRawDirection(text); }).find("--direction '" + std::string(text) + "': the direction matrix is singular"),
                  std::string::npos)
            << text;
    for (const char* text : {"", "nan", "inf", "1e39", "-1e39", "0x10", "air"})
        EXPECT_NE(errorOf([&] { parseRawBackground(text); }).find("--background '" + std::string(text) + "': expected a finite number"),
                  std::string::npos)
            << text;
}

// ---- origin and direction: index -> world ------------------------------------

TEST(RawVolume, OriginAndSpacingPlaceVoxels) {
    RawVolumeSpec spec = specOf(Coord(2, 2, 2), RawType::U8);
    spec.spacing = openvdb::Vec3d(0.5, 2, 3);
    spec.origin = openvdb::Vec3d(-10, 20, 5);
    const auto t = rawTransform(spec);
    EXPECT_TRUE(t->indexToWorld(Coord(0, 0, 0)).eq(openvdb::Vec3d(-10, 20, 5)));
    EXPECT_TRUE(t->indexToWorld(Coord(1, 1, 1)).eq(openvdb::Vec3d(-9.5, 22, 8)));
    EXPECT_TRUE(t->indexToWorld(Coord(4, 0, 2)).eq(openvdb::Vec3d(-8, 20, 11)));
}

// world = origin + direction * diag(spacing) * index, direction given row by
// row: here x steps along world +y, y along world -x, z along world +z.
TEST(RawVolume, DirectionRotatesAndShearsTheAxes) {
    RawVolumeSpec spec = specOf(Coord(2, 2, 2), RawType::U8);
    spec.spacing = openvdb::Vec3d(0.5, 2, 3);
    spec.origin = openvdb::Vec3d(1, 2, 3);
    spec.direction = parseRawDirection("0,-1,0,1,0,0,0,0,1");
    auto t = rawTransform(spec);
    EXPECT_TRUE(t->indexToWorld(Coord(1, 0, 0)).eq(openvdb::Vec3d(1, 2.5, 3))) << t->indexToWorld(Coord(1, 0, 0));
    EXPECT_TRUE(t->indexToWorld(Coord(0, 1, 0)).eq(openvdb::Vec3d(-1, 2, 3))) << t->indexToWorld(Coord(0, 1, 0));
    EXPECT_TRUE(t->indexToWorld(Coord(0, 0, 1)).eq(openvdb::Vec3d(1, 2, 6)));
    EXPECT_TRUE(t->indexToWorld(Coord(2, 3, 4)).eq(openvdb::Vec3d(1 - 6, 2 + 1, 3 + 12)));
    EXPECT_TRUE(t->worldToIndex(openvdb::Vec3d(-5, 3, 15)).eq(openvdb::Vec3d(2, 3, 4)));
    // A shear: z leans along x.
    spec.direction = parseRawDirection("1,0,0.5,0,1,0,0,0,1");
    spec.origin = openvdb::Vec3d(0);
    t = rawTransform(spec);
    EXPECT_TRUE(t->indexToWorld(Coord(0, 0, 2)).eq(openvdb::Vec3d(3, 0, 6))) << t->indexToWorld(Coord(0, 0, 2));
    EXPECT_TRUE(t->indexToWorld(Coord(1, 1, 1)).eq(openvdb::Vec3d(0.5 + 1.5, 2, 3)));
}

TEST(RawVolume, GridCarriesTheAffineTransform) {
    TempDir dir;
    RawVolumeSpec spec = specOf(Coord(2, 2, 2), RawType::U8);
    spec.origin = openvdb::Vec3d(-4, 0, 9);
    spec.direction = parseRawDirection("0,0,1,0,1,0,-1,0,0");
    writeBinary(dir / "v.raw", std::string(8, '\3'));
    const auto grid = readRawVolume((dir / "v.raw").string(), spec);
    EXPECT_TRUE(grid->transform().isLinear());
    EXPECT_TRUE(grid->transform().indexToWorld(Coord(1, 0, 0)).eq(openvdb::Vec3d(-4, 0, 8)));
    EXPECT_TRUE(grid->transform().indexToWorld(Coord(0, 0, 1)).eq(openvdb::Vec3d(-3, 0, 9)));
}
