#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/base/error.hpp"
#include "core/volume/raw_volume.hpp"
#include "tests/support/raw_samples.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;
using namespace weft::test;
using openvdb::Coord;

namespace {

template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

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
    const std::vector<float> values = samplePattern(spec.dims, spec.type);
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
    EXPECT_NE(errorOf([] { parseRawType("u32"); }).find("--type 'u32': unknown sample type (expected u8|u16|f32)"),
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
    const std::vector<float> values = samplePattern(big.dims, big.type);
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
