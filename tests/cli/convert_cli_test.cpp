// `weft convert` end to end: the binary writes a .vdb that OpenVDB reads back
// voxel for voxel; every error exits 1 with one line and leaves the output
// path exactly as it was.
#include <gtest/gtest.h>

#include <openvdb/tools/Count.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <set>

#include "core/volume/volume.hpp"
#include "tests/support/raw_samples.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/volume_files.hpp"

using namespace weft;
using namespace weft::test;
using openvdb::Coord;
namespace fs = std::filesystem;

namespace {

std::string dimsText(const Coord& d) {
    return std::to_string(d.x()) + "," + std::to_string(d.y()) + "," + std::to_string(d.z());
}

std::set<std::string> filesIn(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
}

struct RoundTrip {
    Coord dims;
    RawType type;
    ByteOrder order;
    bool gzip;
    std::string extra;  // further options
};

RoundTrip plain(Coord dims, RawType type, ByteOrder order = ByteOrder::Little) { return {dims, type, order, false, ""}; }
RoundTrip gzipped(Coord dims, RawType type, ByteOrder order = ByteOrder::Little) { return {dims, type, order, true, ""}; }

// Converts the sample pattern with the binary and returns the grid it wrote.
openvdb::FloatGrid::Ptr convertPattern(const TempDir& dir, const RoundTrip& t, std::vector<double>& values) {
    values = samplePattern(t.dims, t.type);
    const std::string bytes = encodeSamples(values, t.type, t.order);
    const fs::path in = dir / (t.gzip ? "in.raw.gz" : "in.raw");
    t.gzip ? writeGzip(in, bytes) : writeBinary(in, bytes);
    const fs::path out = dir / "out.vdb";
    const CommandResult r = runWeft("convert " + in.string() + " --dims " + dimsText(t.dims) + " --type " +
                                    rawTypeName(t.type) + " --endian " + (t.order == ByteOrder::Big ? "big" : "little") +
                                    " " + t.extra + " -o " + out.string());
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(out.string()), std::string::npos) << r.output;
    if (r.status != 0) return nullptr;
    return readFloatGrid(out.string(), "");
}

void expectRoundTrip(const RoundTrip& t) {
    TempDir dir;
    std::vector<double> values;
    const auto grid = convertPattern(dir, t, values);
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->getName(), "density");
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_FALSE(grid->saveFloatAsHalf());
    EXPECT_TRUE(grid->transform().voxelSize().eq(openvdb::Vec3d(1, 1, 1)));
    expectGridHolds(*grid, t.dims, values);
    EXPECT_EQ(filesIn(dir.path()), (std::set<std::string>{t.gzip ? "in.raw.gz" : "in.raw", "out.vdb"}));
}

// An error case: a folder with the inputs the case needs, then the same
// command run twice, once with no output file and once over an existing one.
class ConvertError : public ::testing::Test {
protected:
    TempDir dir;
    std::string in(const std::string& name) const { return (dir / name).string(); }

    void expectFailure(const std::string& args, const std::string& message, const std::string& output = "out.vdb") {
        const fs::path out = dir / output;
        const std::set<std::string> before = filesIn(dir.path());
        CommandResult r = runWeft("convert " + args + " -o " + out.string());
        EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("weft: error: "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_EQ(filesIn(dir.path()), before) << "a failed run left a file: " << args;

        if (!fs::is_directory(out.parent_path())) return;
        const std::string precious = "an earlier result, not to be touched\n";
        writeText(out, precious);
        r = runWeft("convert " + args + " -o " + out.string());
        EXPECT_EQ(r.status, 1) << r.output;
        EXPECT_EQ(readBytes(out), precious) << args;
        fs::remove(out);
        EXPECT_EQ(filesIn(dir.path()), before) << "a failed run left a file: " << args;
    }
};

}  // namespace

TEST(ConvertCli, RoundTripU8) { expectRoundTrip(plain(Coord(13, 7, 10), RawType::U8)); }
TEST(ConvertCli, RoundTripU16LittleEndian) { expectRoundTrip(plain(Coord(9, 12, 5), RawType::U16, ByteOrder::Little)); }
TEST(ConvertCli, RoundTripU16BigEndian) { expectRoundTrip(plain(Coord(9, 12, 5), RawType::U16, ByteOrder::Big)); }
TEST(ConvertCli, RoundTripF32) { expectRoundTrip(plain(Coord(10, 10, 10), RawType::F32)); }
TEST(ConvertCli, RoundTripF32BigEndian) { expectRoundTrip(plain(Coord(6, 5, 17), RawType::F32, ByteOrder::Big)); }
TEST(ConvertCli, RoundTripGzipU8) { expectRoundTrip(gzipped(Coord(20, 18, 9), RawType::U8)); }
TEST(ConvertCli, RoundTripGzipU16BigEndian) { expectRoundTrip(gzipped(Coord(20, 18, 9), RawType::U16, ByteOrder::Big)); }

TEST(ConvertCli, SpacingAndGridName) {
    TempDir dir;
    std::vector<double> values;
    const auto grid = convertPattern(dir, {Coord(6, 6, 6), RawType::U8, ByteOrder::Little, false,
                                           "--spacing 0.5,0.25,2 --grid ct"}, values);
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->getName(), "ct");
    EXPECT_TRUE(grid->transform().voxelSize().eq(openvdb::Vec3d(0.5, 0.25, 2)));
    EXPECT_TRUE(grid->transform().indexToWorld(Coord(2, 4, 1)).eq(openvdb::Vec3d(1, 1, 2)));
    expectGridHolds(*grid, Coord(6, 6, 6), values);
}

TEST(ConvertCli, UniformSpacing) {
    TempDir dir;
    std::vector<double> values;
    const auto grid = convertPattern(dir, {Coord(4, 4, 4), RawType::U8, ByteOrder::Little, false, "--spacing 0.1,0.1,0.1"}, values);
    ASSERT_TRUE(grid);
    EXPECT_TRUE(grid->transform().voxelSize().eq(openvdb::Vec3d(0.1, 0.1, 0.1)));
}

TEST(ConvertCli, ZerosAreInactiveBackground) {
    TempDir dir;
    // A 16^3 block of zeros with one value: one active voxel, no leaf for the rest.
    std::string bytes(16 * 16 * 16, '\0');
    bytes[voxelIndex(Coord(16, 16, 16), 3, 9, 12)] = char(200);
    writeBinary(dir / "in.raw", bytes);
    const CommandResult r = runWeft("convert " + (dir / "in.raw").string() + " --dims 16,16,16 --type u8 -o " +
                                    (dir / "out.vdb").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("1 active voxels"), std::string::npos) << r.output;
    const auto grid = readFloatGrid((dir / "out.vdb").string(), "density");
    EXPECT_EQ(grid->activeVoxelCount(), 1u);
    EXPECT_EQ(grid->tree().leafCount(), 1u);
    EXPECT_EQ(grid->background(), 0.0f);
    EXPECT_EQ(grid->tree().getValue(Coord(3, 9, 12)), 200.0f);
    EXPECT_FALSE(grid->tree().isValueOn(Coord(3, 9, 11)));
}

TEST(ConvertCli, SummaryNamesDimsCountRangeAndOutput) {
    TempDir dir;
    writeBinary(dir / "in.raw", std::string("\0\3\0\x09\0\0\0\0", 8));
    const std::string out = (dir / "out.vdb").string();
    const CommandResult r = runWeft("convert " + (dir / "in.raw").string() + " --dims 2,2,2 --type u8 -o " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    for (const std::string& s : std::vector<std::string>{"2x2x2 u8", "2 active voxels", "values 3..9", out})
        EXPECT_NE(r.output.find(s), std::string::npos) << s << " in " << r.output;
}

TEST(ConvertCli, ReplacesAnExistingOutput) {
    TempDir dir;
    writeText(dir / "out.vdb", "old");
    writeBinary(dir / "in.raw", std::string(8, '\5'));
    const CommandResult r = runWeft("convert " + (dir / "in.raw").string() + " --dims 2,2,2 --type u8 -o " +
                                    (dir / "out.vdb").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(readFloatGrid((dir / "out.vdb").string(), "")->activeVoxelCount(), 8u);
}

TEST(ConvertCli, ListedInHelp) {
    const CommandResult r = runWeft("--help");
    EXPECT_NE(r.output.find("convert"), std::string::npos) << r.output;
}

TEST_F(ConvertError, MissingInput) {
    expectFailure(in("none.raw") + " --dims 2,2,2 --type u8", "raw volume '" + in("none.raw") + "': no such file");
}

TEST_F(ConvertError, SizeMismatchNamesBothNumbers) {
    writeBinary(dir / "v.raw", std::string(59, '\1'));
    expectFailure(in("v.raw") + " --dims 5,4,3 --type u8", "v.raw: holds 59 bytes but --dims 5,4,3 --type u8 needs 60");
    expectFailure(in("v.raw") + " --dims 5,4,3 --type u16", "v.raw: holds 59 bytes but --dims 5,4,3 --type u16 needs 120");
}

TEST_F(ConvertError, GzipSizeMismatch) {
    writeGzip(dir / "v.raw.gz", std::string(61, '\1'));
    expectFailure(in("v.raw.gz") + " --dims 5,4,3 --type u8", "v.raw.gz: unpacks to 61 bytes but --dims 5,4,3 --type u8 needs 60");
    expectFailure(in("v.raw.gz") + " --dims 8,4,3 --type u8", "v.raw.gz: unpacks to 61 bytes but --dims 8,4,3 --type u8 needs 96");
}

TEST_F(ConvertError, CorruptGzip) {
    const std::vector<double> values = samplePattern(Coord(32, 32, 32), RawType::U8);
    writeGzip(dir / "good.raw.gz", encodeSamples(values, RawType::U8, ByteOrder::Little));
    const std::string good = readBytes(dir / "good.raw.gz");
    writeBinary(dir / "notgz.raw.gz", std::string(32768, '\1'));
    writeBinary(dir / "cut.raw.gz", good.substr(0, good.size() / 2));
    std::string flipped = good;
    for (std::size_t i = 40; i < 60; ++i) flipped[i] = char(~flipped[i]);
    writeBinary(dir / "flipped.raw.gz", flipped);
    expectFailure(in("notgz.raw.gz") + " --dims 32,32,32 --type u8", "notgz.raw.gz: not gzip data");
    expectFailure(in("cut.raw.gz") + " --dims 32,32,32 --type u8", "cut.raw.gz: truncated gzip data");
    expectFailure(in("flipped.raw.gz") + " --dims 32,32,32 --type u8", "flipped.raw.gz: corrupt gzip data");
}

TEST_F(ConvertError, BadDims) {
    writeBinary(dir / "v.raw", std::string(8, '\1'));
    for (const std::string dims : {"2,2", "2,2,2,1", "0,2,2", "2,-2,2", "a,b,c", "2.5,2,2", "''"})
        expectFailure(in("v.raw") + " --dims " + dims + " --type u8", "expected 3 positive integers X,Y,Z");
}

TEST_F(ConvertError, BadSpacing) {
    writeBinary(dir / "v.raw", std::string(8, '\1'));
    for (const std::string spacing : {"1,1", "1,1,1,1", "0,1,1", "1,-1,1", "nan,1,1", "1,inf,1", "x,y,z"})
        expectFailure(in("v.raw") + " --dims 2,2,2 --type u8 --spacing " + spacing, "expected 3 positive numbers sx,sy,sz");
}

TEST_F(ConvertError, AbsurdSizes) {
    writeBinary(dir / "v.raw", std::string(8, '\1'));
    expectFailure(in("v.raw") + " --dims 1073741824,1073741824,1073741824 --type u8", "the volume size overflows 64 bits");
    expectFailure(in("v.raw") + " --dims 1073741824,1073741824,2 --type f32", "more than the 1 TiB weft accepts");
    expectFailure(in("v.raw") + " --dims 5000000000,1,1 --type u8", "5000000000 voxels along an axis is more than weft accepts");
    expectFailure(in("v.raw") + " --dims 1,1,123456789012345678901234567890 --type u8", "more than weft accepts");
}

TEST_F(ConvertError, UnknownTypeAndByteOrder) {
    writeBinary(dir / "v.raw", std::string(8, '\1'));
    expectFailure(in("v.raw") + " --dims 2,2,2 --type u64",
                  "--type 'u64': unknown sample type (expected u8|i8|u16|i16|u32|i32|f32|f64)");
    expectFailure(in("v.raw") + " --dims 2,2,2 --type u8 --endian middle", "--endian 'middle': unknown byte order");
}

TEST_F(ConvertError, OutputMustBeVdb) {
    writeBinary(dir / "v.raw", std::string(8, '\1'));
    expectFailure(in("v.raw") + " --dims 2,2,2 --type u8", "must end in .vdb", "out.exr");
    expectFailure(in("v.raw") + " --dims 2,2,2 --type u8", "must end in .vdb", "out");
}

TEST_F(ConvertError, OutputFolderMissing) {
    writeBinary(dir / "v.raw", std::string(8, '\1'));
    expectFailure(in("v.raw") + " --dims 2,2,2 --type u8", "does not exist", "no/such/folder/out.vdb");
    EXPECT_FALSE(fs::exists(dir / "no"));
}

TEST_F(ConvertError, NonFiniteFloat) {
    std::vector<float> values(8, 0.5f);
    values[5] = std::numeric_limits<float>::infinity();
    writeBinary(dir / "v.raw", encodeSamples(values, RawType::F32, ByteOrder::Little));
    expectFailure(in("v.raw") + " --dims 2,2,2 --type f32", "voxel (1,0,1) holds inf; densities must be finite");
}

TEST_F(ConvertError, EmptyGridName) {
    writeBinary(dir / "v.raw", std::string(8, '\1'));
    expectFailure(in("v.raw") + " --dims 2,2,2 --type u8 --grid ''", "grid name must not be empty");
}

TEST(ConvertCli, EverySampleTypeWithItsExtremes) {
    for (RawType type : kAllRawTypes) {
        SCOPED_TRACE(rawTypeName(type));
        expectRoundTrip(plain(Coord(7, 5, 3), type, ByteOrder::Big));
    }
}

// CT in Hounsfield units: air (-1000) is the inactive background, water (0)
// a value like any other, and the scanner's geometry places the voxels.
TEST(ConvertCli, HounsfieldVolumeWithBackgroundOriginAndDirection) {
    TempDir dir;
    std::vector<double> values(4 * 4 * 2, -1000.0);
    values[voxelIndex(Coord(4, 4, 2), 1, 2, 1)] = 0;
    values[voxelIndex(Coord(4, 4, 2), 3, 0, 0)] = -32768;
    values[voxelIndex(Coord(4, 4, 2), 0, 3, 1)] = 3071;
    writeBinary(dir / "ct.raw", encodeSamples(values, RawType::I16, ByteOrder::Little));
    const std::string out = (dir / "ct.vdb").string();
    const CommandResult r = runWeft("convert " + (dir / "ct.raw").string() +
                                    " --dims 4,4,2 --type i16 --background -1000 --spacing 0.5,0.5,2 --origin -100,-50,10"
                                    " --direction 0,-1,0,1,0,0,0,0,1 -o " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("3 active voxels, values -32768..3071"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("background -1000"), std::string::npos) << r.output;
    const auto grid = readFloatGrid(out, "density");
    expectGridHolds(*grid, Coord(4, 4, 2), values, -1000.0f);
    // x steps along world +y, y along world -x.
    EXPECT_TRUE(grid->transform().indexToWorld(Coord(1, 2, 1)).eq(openvdb::Vec3d(-101, -49.5, 12)))
        << grid->transform().indexToWorld(Coord(1, 2, 1));
}

TEST(ConvertCli, SelfDescribingFormats) {
    TempDir dir;
    const Coord dims(6, 5, 4);
    const auto values = samplePattern(dims, RawType::I16);
    const std::string little = encodeSamples(values, RawType::I16, ByteOrder::Little);
    const std::string big = encodeSamples(values, RawType::I16, ByteOrder::Big);
    writeBinary(dir / "a.nrrd", nrrdHeader(nrrdFields("short", dims, "little", "gzip") + "spacings: 1 1 2\n") + gzipBytes(little));
    writeBinary(dir / "b.raw", big);
    writeText(dir / "b.nhdr", nrrdHeader(nrrdFields("int16", dims, "big") + "data file: b.raw\n", false));
    writeBinary(dir / "c.npy", npyFile(npyDict("<i2", false, "(4, 5, 6)"), little));
    writeBinary(dir / "d.vtk", vtkHeader("BINARY", dims, "short") + big + "\n");
    for (const char* name : {"a.nrrd", "b.nhdr", "c.npy", "d.vtk"}) {
        SCOPED_TRACE(name);
        const std::string out = (dir / "out.vdb").string();
        const CommandResult r = runWeft("convert " + (dir / name).string() + " --grid ct -o " + out);
        ASSERT_EQ(r.status, 0) << r.output;
        EXPECT_NE(r.output.find("6x5x4 i16"), std::string::npos) << r.output;
        expectGridHolds(*readFloatGrid(out, "ct"), dims, values);
    }
}

TEST_F(ConvertError, HeaderContradictedOrBroken) {
    const auto values = samplePattern(Coord(2, 2, 2), RawType::U8);
    writeBinary(dir / "v.nrrd", nrrdHeader(nrrdFields("uchar", Coord(2, 2, 2))) + encodeSamples(values, RawType::U8, ByteOrder::Little));
    expectFailure(in("v.nrrd") + " --dims 2,2,3", "--dims '2,2,3' contradicts the header of " + in("v.nrrd") + " (sizes 2,2,2)");
    expectFailure(in("v.nrrd") + " --type i8", "--type 'i8' contradicts the header");
    writeBinary(dir / "b.nrrd", nrrdHeader(nrrdFields("uchar", Coord(2, 2, 2), "little", "bzip2")) + std::string(8, '\1'));
    expectFailure(in("b.nrrd"), "b.nrrd: NRRD field 'encoding' 'bzip2': not supported");
    writeBinary(dir / "v.raw", std::string(8, '\1'));
    expectFailure(in("v.raw"), "a headerless volume needs --dims and --type");
    expectFailure(in("v.raw") + " --dims 2,2,2 --type u8 --direction 1,0,0,0,1,0,0,0,0", "--direction '1,0,0,0,1,0,0,0,0': the direction matrix is singular");
    expectFailure(in("v.raw") + " --dims 2,2,2 --type u8 --origin 1,2", "--origin '1,2': expected 3 finite numbers");
    expectFailure(in("v.raw") + " --dims 2,2,2 --type u8 --background nan", "--background 'nan': expected a finite number");
}

TEST(ConvertCli, HelpListsTypesOptionsAndFormats) {
    const CommandResult r = runWeft("convert --help");
    for (const char* s : {"u8|i8|u16|i16|u32|i32|f32|f64", "--origin", "--direction", "--background", ".nrrd", ".nhdr", ".npy", ".vtk"})
        EXPECT_NE(r.output.find(s), std::string::npos) << s << " in " << r.output;
}

TEST(ConvertCli, Aneurism) {
    const std::string data = sharedDataDir();
    if (data.empty() || !fs::exists(fs::path(data) / "aneurism.raw.gz")) GTEST_SKIP() << "no ../shared/data/aneurism.raw.gz";
    TempDir dir;
    const std::string out = (dir / "aneurism.vdb").string();
    const CommandResult r = runWeft("convert " + (fs::path(data) / "aneurism.raw.gz").string() +
                                    " --dims 256,256,256 --type u8 -o " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    std::printf("%s", r.output.c_str());
    EXPECT_NE(r.output.find("168948 active voxels, values 1..255"), std::string::npos) << r.output;
    const auto grid = readFloatGrid(out, "density");
    EXPECT_EQ(grid->activeVoxelCount(), 168948u);
    const auto range = openvdb::tools::minMax(grid->tree());
    EXPECT_EQ(range.min(), 1.0f);
    EXPECT_EQ(range.max(), 255.0f);
    EXPECT_TRUE(openvdb::CoordBBox(Coord(0), Coord(255)).isInside(grid->evalActiveVoxelBoundingBox()));
}

namespace {

// Spacings and origins outside the ranges a volume may be placed in are
// refused in weft's words (OpenVDB's ArithmeticError text reached the user),
// and the input is never the output.
TEST(ConvertCli, PlacementOutsideTheRangesIsRefusedInOwnWords) {
    TempDir dir;
    writeBinary(dir / "in.raw", std::string(8, '\5'));
    const std::string base = "convert " + (dir / "in.raw").string() + " --dims 2,2,2 --type u8 -o " + (dir / "out.vdb").string();
    const std::pair<std::string, std::string> cases[] = {
        {" --spacing 1e-30,1,1", "voxel spacing 1e-30,1,1 is outside [1e-08, 1e+08]"},
        {" --origin 1e300,0,0", "origin 1e+300,0,0 lies beyond the +-1e+12 units"},
    };
    for (const auto& [args, words] : cases) {
        const CommandResult r = runWeft(base + args);
        EXPECT_NE(r.status, 0) << args;
        EXPECT_NE(r.output.find(words), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("ArithmeticError"), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "out.vdb"));
    }
    writeBinary(dir / "self.vdb", std::string(8, '\5'));
    const CommandResult self = runWeft("convert " + (dir / "self.vdb").string() + " --dims 2,2,2 --type u8 -o " + (dir / "self.vdb").string());
    EXPECT_NE(self.status, 0);
    EXPECT_NE(self.output.find("this run reads"), std::string::npos) << self.output;
    EXPECT_EQ(readBytes(dir / "self.vdb"), std::string(8, '\5'));
}

}  // namespace
