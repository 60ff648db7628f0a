// NRRD, NumPy and VTK import: each format's samples reach the grid with
// their values and geometry, and hostile headers are rejected with one line
// naming the file and the field, before any large allocation.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <filesystem>

#include "core/base/error.hpp"
#include "core/volume/io/npy_header.hpp"
#include "core/volume/io/nrrd_header.hpp"
#include "core/volume/io/raw_samples.hpp"
#include "core/volume/io/volume_import.hpp"
#include "core/volume/io/vtk_image_header.hpp"
#include "tests/support/raw_samples.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/volume_files.hpp"

using namespace weft;
using namespace weft::test;
using openvdb::Coord;
using openvdb::Vec3d;
namespace fs = std::filesystem;

namespace {


openvdb::FloatGrid::Ptr importGrid(const fs::path& path, const ImportOptions& options = {}) {
    const VolumeImport im = planImport(path.string(), options);
    return readVolumeSamples(im.data, im.spec);
}

std::string importError(const fs::path& path, const ImportOptions& options = {}) {
    return errorOf([&] { importGrid(path, options); });
}

const Coord kDims(5, 4, 3);

}  // namespace

// ---- NRRD ------------------------------------------------------------------

TEST(NrrdImport, AttachedRawBigEndianShortWithGeometry) {
    TempDir dir;
    const auto values = samplePattern(kDims, RawType::I16);
    const std::string fields = nrrdFields("short", kDims, "big") +
                               "space: left-posterior-superior\nspace directions: (0.5,0,0) (0,0.75,0) (0,0,2.5)\n"
                               "space origin: (-10,20.5,3)\nkinds: domain domain domain\nct:=yes\n";
    writeBinary(dir / "ct.nrrd", nrrdHeader(fields) + encodeSamples(values, RawType::I16, ByteOrder::Big));
    const auto grid = importGrid(dir / "ct.nrrd");
    expectGridHolds(*grid, kDims, values);
    EXPECT_TRUE(grid->transform().indexToWorld(Coord(0, 0, 0)).eq(Vec3d(-10, 20.5, 3)));
    EXPECT_TRUE(grid->transform().indexToWorld(Coord(2, 4, 1)).eq(Vec3d(-9, 23.5, 5.5)));
}

TEST(NrrdImport, AttachedGzipFloats) {
    TempDir dir;
    const auto values = samplePattern(kDims, RawType::F32);
    writeBinary(dir / "v.nrrd", nrrdHeader(nrrdFields("float", kDims, "little", "gzip") + "spacings: 1 2 3\n") +
                                    gzipBytes(encodeSamples(values, RawType::F32, ByteOrder::Little)));
    const auto grid = importGrid(dir / "v.nrrd");
    expectGridHolds(*grid, kDims, values);
    EXPECT_TRUE(grid->transform().voxelSize().eq(Vec3d(1, 2, 3)));
}

TEST(NrrdImport, DetachedHeaderNamesItsDataRelativeToItself) {
    TempDir dir;
    fs::create_directory(dir / "hdr");
    fs::create_directory(dir / "hdr" / "data");
    const auto values = samplePattern(kDims, RawType::U16);
    writeBinary(dir / "hdr" / "data" / "v.raw", encodeSamples(values, RawType::U16, ByteOrder::Little));
    writeText(dir / "hdr" / "v.nhdr", nrrdHeader(nrrdFields("unsigned short", kDims) + "data file: data/v.raw\n", false));
    expectGridHolds(*importGrid(dir / "hdr" / "v.nhdr"), kDims, values);
    // gzip, and the old field spelling.
    writeGzip(dir / "hdr" / "data" / "v.raw.gz", encodeSamples(values, RawType::U16, ByteOrder::Big));
    writeText(dir / "hdr" / "z.nhdr", nrrdHeader(nrrdFields("uint16", kDims, "big", "gz") + "datafile: data/v.raw.gz\n"));
    expectGridHolds(*importGrid(dir / "hdr" / "z.nhdr"), kDims, values);
}

TEST(NrrdImport, LineSkipAndByteSkip) {
    TempDir dir;
    const auto values = samplePattern(kDims, RawType::I8);
    const std::string samples = encodeSamples(values, RawType::I8, ByteOrder::Little);
    writeBinary(dir / "v.dat", "line one\nline two\nXYZ" + samples);
    writeText(dir / "a.nhdr", nrrdHeader(nrrdFields("signed char", kDims) + "data file: v.dat\nline skip: 2\nbyte skip: 3\n"));
    expectGridHolds(*importGrid(dir / "a.nhdr"), kDims, values);
    writeText(dir / "b.nhdr", nrrdHeader(nrrdFields("int8", kDims) + "data file: v.dat\nbyte skip: -1\n"));
    expectGridHolds(*importGrid(dir / "b.nhdr"), kDims, values);
    writeGzip(dir / "v.dat.gz", "12345" + samples);
    writeText(dir / "c.nhdr", nrrdHeader(nrrdFields("int8_t", kDims, "little", "gzip") + "data file: v.dat.gz\nbyte skip: 5\n"));
    expectGridHolds(*importGrid(dir / "c.nhdr"), kDims, values);
}

TEST(NrrdImport, EveryTypeSpelling) {
    const std::vector<std::pair<std::string, RawType>> spellings = {
        {"signed char", RawType::I8}, {"int8", RawType::I8}, {"int8_t", RawType::I8}, {"uchar", RawType::U8},
        {"unsigned char", RawType::U8}, {"uint8", RawType::U8}, {"uint8_t", RawType::U8}, {"short", RawType::I16},
        {"short int", RawType::I16}, {"signed short", RawType::I16}, {"signed short int", RawType::I16},
        {"int16", RawType::I16}, {"int16_t", RawType::I16}, {"ushort", RawType::U16}, {"unsigned short", RawType::U16},
        {"unsigned short int", RawType::U16}, {"uint16", RawType::U16}, {"uint16_t", RawType::U16}, {"int", RawType::I32},
        {"signed int", RawType::I32}, {"int32", RawType::I32}, {"int32_t", RawType::I32}, {"uint", RawType::U32},
        {"unsigned int", RawType::U32}, {"uint32", RawType::U32}, {"uint32_t", RawType::U32}, {"float", RawType::F32},
        {"double", RawType::F64}};
    for (const auto& [name, type] : spellings) {
        const NrrdHeader h = parseNrrdHeader(nrrdHeader(nrrdFields(name, kDims, "big")), true, "t.nrrd");
        EXPECT_EQ(h.volume.spec.type, type) << name;
        EXPECT_EQ(h.volume.spec.byteOrder, ByteOrder::Big) << name;
        EXPECT_EQ(h.volume.spec.dims, kDims) << name;
    }
}

TEST(NrrdImport, EveryTypeRoundTripsWithItsExtremes) {
    const std::vector<std::pair<std::string, RawType>> types = {{"uchar", RawType::U8}, {"signed char", RawType::I8},
        {"ushort", RawType::U16}, {"short", RawType::I16}, {"uint", RawType::U32}, {"int", RawType::I32},
        {"float", RawType::F32}, {"double", RawType::F64}};
    TempDir dir;
    for (const auto& [name, type] : types) {
        const auto values = samplePattern(kDims, type);
        writeBinary(dir / "v.nrrd", nrrdHeader(nrrdFields(name, kDims, "big")) + encodeSamples(values, type, ByteOrder::Big));
        SCOPED_TRACE(name);
        expectGridHolds(*importGrid(dir / "v.nrrd"), kDims, values);
    }
}

// ---- NumPy -----------------------------------------------------------------

// C order: shape (Z, Y, X), the last axis fastest; Fortran order: shape
// (X, Y, Z), the first axis fastest. Both are weft's x-fastest bytes.
TEST(NpyImport, COrderAndFortranOrderMapTheFastestAxisToX) {
    TempDir dir;
    const auto values = samplePattern(kDims, RawType::I16);
    const std::string bytes = encodeSamples(values, RawType::I16, ByteOrder::Little);
    writeBinary(dir / "c.npy", npyFile(npyDict("<i2", false, "(3, 4, 5)"), bytes));
    writeBinary(dir / "f.npy", npyFile(npyDict("<i2", true, "(5, 4, 3)"), bytes));
    for (const char* name : {"c.npy", "f.npy"}) {
        SCOPED_TRACE(name);
        const VolumeImport im = planImport((dir / name).string(), {});
        EXPECT_EQ(im.spec.dims, kDims);
        EXPECT_EQ(im.format, "npy");
        expectGridHolds(*readVolumeSamples(im.data, im.spec), kDims, values);
    }
}

TEST(NpyImport, EveryDtypeAndVersion) {
    const std::vector<std::pair<std::string, RawType>> dtypes = {{"|u1", RawType::U8}, {"|i1", RawType::I8},
        {"<u2", RawType::U16}, {">i2", RawType::I16}, {"<u4", RawType::U32}, {">i4", RawType::I32},
        {"<f4", RawType::F32}, {">f8", RawType::F64}};
    TempDir dir;
    for (int version = 1; version <= 3; ++version)
        for (const auto& [descr, type] : dtypes) {
            const ByteOrder order = descr[0] == '>' ? ByteOrder::Big : ByteOrder::Little;
            const auto values = samplePattern(kDims, type);
            writeBinary(dir / "v.npy", npyFile("{\"shape\": (3,4,5), \"fortran_order\": False, \"descr\": \"" + descr + "\"}",
                                               encodeSamples(values, type, order), version));
            SCOPED_TRACE(descr + " v" + std::to_string(version));
            expectGridHolds(*importGrid(dir / "v.npy"), kDims, values);
        }
}

// ---- VTK -------------------------------------------------------------------

TEST(VtkImport, BinaryBigEndianWithSpacingAndOrigin) {
    TempDir dir;
    const auto values = samplePattern(kDims, RawType::I16);
    writeBinary(dir / "v.vtk", vtkHeader("BINARY", kDims, "short", "SPACING 0.5 1 2\nORIGIN -1 -2 -3\n") +
                                   encodeSamples(values, RawType::I16, ByteOrder::Big) + "\nVECTORS other float\n");
    const auto grid = importGrid(dir / "v.vtk");
    expectGridHolds(*grid, kDims, values);
    EXPECT_TRUE(grid->transform().indexToWorld(Coord(2, 1, 1)).eq(Vec3d(0, -1, -1)));
}

TEST(VtkImport, AsciiAndTheAspectRatioAlias) {
    TempDir dir;
    const auto values = samplePattern(kDims, RawType::F32);
    std::string text;
    for (std::size_t i = 0; i < values.size(); ++i) {
        char buf[48];
        std::snprintf(buf, sizeof buf, "%.9g%s", values[i], i % 7 == 6 ? "\n" : " ");
        text += buf;
    }
    writeText(dir / "v.vtk", vtkHeader("ASCII", kDims, "float", "ASPECT_RATIO 2 2 2\nORIGIN 0 0 1\n") + text + "\n");
    const auto grid = importGrid(dir / "v.vtk");
    expectGridHolds(*grid, kDims, values);
    EXPECT_TRUE(grid->transform().indexToWorld(Coord(1, 1, 1)).eq(Vec3d(2, 2, 3)));
    // Integer types hold integers in their range, including the extremes.
    const auto shorts = samplePattern(kDims, RawType::I16);
    text.clear();
    for (double v : shorts) text += std::to_string(int(v)) + "\n";
    writeText(dir / "s.vtk", vtkHeader("ascii", kDims, "short") + text);
    expectGridHolds(*importGrid(dir / "s.vtk"), kDims, shorts);
}

// ---- options beside a header -------------------------------------------------

TEST(VolumeImportOptions, ComplementButDoNotContradictTheHeader) {
    TempDir dir;
    const auto values = samplePattern(kDims, RawType::I16);
    writeBinary(dir / "v.npy", npyFile(npyDict("<i2", false, "(3, 4, 5)"), encodeSamples(values, RawType::I16, ByteOrder::Little)));
    ImportOptions o;
    o.grid = "ct";
    o.spacing = "0.5,0.5,1";  // npy has no geometry: these complement it
    o.origin = "1,2,3";
    o.direction = "0,1,0,1,0,0,0,0,-1";
    o.background = "-1000";
    o.dims = "5,4,3";  // as the header says: fine
    o.type = "i16";
    const VolumeImport im = planImport((dir / "v.npy").string(), o);
    EXPECT_EQ(im.spec.gridName, "ct");
    EXPECT_EQ(im.spec.background, -1000.0);
    EXPECT_TRUE(rawTransform(im.spec)->indexToWorld(Coord(1, 1, 1)).eq(Vec3d(1.5, 2.5, 2)));

    ImportOptions bad;
    bad.dims = "3,4,5";
    EXPECT_EQ(importError(dir / "v.npy", bad),
              "--dims '3,4,5' contradicts the header of " + (dir / "v.npy").string() + " (sizes 5,4,3)");
    bad = {};
    bad.type = "u16";
    EXPECT_NE(importError(dir / "v.npy", bad).find("--type 'u16' contradicts the header"), std::string::npos);
    bad = {};
    bad.endian = "big";
    EXPECT_NE(importError(dir / "v.npy", bad).find("--endian 'big' contradicts the header"), std::string::npos);

    writeBinary(dir / "v.vtk", vtkHeader("BINARY", kDims, "short", "SPACING 1 1 2\nORIGIN 0 0 0\n") +
                                   encodeSamples(values, RawType::I16, ByteOrder::Big));
    bad = {};
    bad.spacing = "1,1,1";
    EXPECT_NE(importError(dir / "v.vtk", bad).find("--spacing '1,1,1' contradicts the header"), std::string::npos);
    bad = {};
    bad.origin = "0,0,1";
    EXPECT_NE(importError(dir / "v.vtk", bad).find("--origin '0,0,1' contradicts the header"), std::string::npos);
    bad = {};
    bad.spacing = "1,1,2";
    EXPECT_EQ(importError(dir / "v.vtk", bad), "");

    writeBinary(dir / "d.nrrd", nrrdHeader(nrrdFields("short", kDims) + "space directions: (0,1,0) (1,0,0) (0,0,1)\n") +
                                    encodeSamples(values, RawType::I16, ByteOrder::Little));
    bad = {};
    bad.direction = "1,0,0,0,1,0,0,0,1";
    EXPECT_NE(importError(dir / "d.nrrd", bad).find("--direction '1,0,0,0,1,0,0,0,1' contradicts the header"), std::string::npos);
}

TEST(VolumeImportOptions, RawFilesNeedDimsAndType) {
    TempDir dir;
    writeBinary(dir / "v.raw", std::string(8, '\1'));
    EXPECT_NE(importError(dir / "v.raw").find("a headerless volume needs --dims and --type"), std::string::npos);
}

// ---- hostile headers -------------------------------------------------------------

struct BadFile {
    std::string name;
    std::string bytes;
    std::string message;
};

std::vector<BadFile> badNrrds() {
    const std::string s8(60, '\1');
    const auto f = [](const std::string& type = "uchar") { return nrrdFields(type, kDims); };
    const std::string bigHeader = "NRRD0004\n" + std::string(kMaxHeaderBytes + 10, '#');
    return {
        {"magic.nrrd", "NRRD0006\n" + f() + "\n" + s8, "not a NRRD file"},
        {"empty.nrrd", "", "not a NRRD file"},
        {"notype.nrrd", nrrdHeader("dimension: 3\nsizes: 5 4 3\nencoding: raw\n") + s8, "has no 'type' field"},
        {"int64.nrrd", nrrdHeader(f("int64")) + s8, "NRRD field 'type' 'int64': not supported"},
        {"block.nrrd", nrrdHeader(f("block")) + s8, "NRRD field 'type' 'block': not supported"},
        {"char.nrrd", nrrdHeader(f("char")) + s8, "NRRD field 'type' 'char': not a NRRD type"},
        {"bzip.nrrd", nrrdHeader(nrrdFields("uchar", kDims, "little", "bzip2")) + s8, "NRRD field 'encoding' 'bzip2': not supported"},
        {"ascii.nrrd", nrrdHeader(nrrdFields("uchar", kDims, "little", "ascii")) + s8, "NRRD field 'encoding' 'ascii': not supported"},
        {"hex.nrrd", nrrdHeader(nrrdFields("uchar", kDims, "little", "hex")) + s8, "NRRD field 'encoding' 'hex': not supported"},
        {"dim4.nrrd", nrrdHeader("type: uchar\ndimension: 4\nsizes: 1 5 4 3\nencoding: raw\n") + s8,
         "NRRD field 'dimension' '4': weft reads 3-dimensional scalar volumes only"},
        {"sizes2.nrrd", nrrdHeader("type: uchar\ndimension: 3\nsizes: 5 4\nencoding: raw\n") + s8, "NRRD field 'sizes' '5 4': expected 3 sizes"},
        {"sizes0.nrrd", nrrdHeader("type: uchar\ndimension: 3\nsizes: 5 0 3\nencoding: raw\n") + s8, "NRRD field 'sizes' '0': expected an integer from 1"},
        {"sizesbig.nrrd", nrrdHeader("type: uchar\ndimension: 3\nsizes: 99999999999999999999 4 3\nencoding: raw\n") + s8, "expected an integer"},
        {"huge.nrrd", nrrdHeader("type: uchar\ndimension: 3\nsizes: 1073741824 1073741824 2\nencoding: raw\n") + s8, "more than the 1 TiB"},
        {"lying.nrrd", nrrdHeader("type: short\ndimension: 3\nsizes: 1024 1024 1024\nencoding: raw\nendian: little\n") + s8,
         "lying.nrrd: holds 60 bytes after its"},
        {"noendian.nrrd", nrrdHeader("type: short\ndimension: 3\nsizes: 5 4 3\nencoding: raw\n") + s8, "has no 'endian' field"},
        {"endian.nrrd", nrrdHeader(nrrdFields("short", kDims, "middle")) + s8, "NRRD field 'endian' 'middle'"},
        {"list.nrrd", nrrdHeader(f() + "data file: LIST\n") + s8, "NRRD field 'data file' 'LIST': several data files"},
        {"format.nrrd", nrrdHeader(f() + "data file: slice%03d.raw 1 3 1\n") + s8, "several data files"},
        {"unknown.nrrd", nrrdHeader(f() + "colour: red\n") + s8, "'colour' is not a NRRD field"},
        {"twice.nrrd", nrrdHeader(f() + "sizes: 5 4 3\n") + s8, "NRRD field 'sizes' is given twice"},
        {"nospace.nrrd", nrrdHeader(f() + "sizes=5\n") + s8, "is not 'field: value'"},
        {"nanspacing.nrrd", nrrdHeader(f() + "spacings: 1 nan 1\n") + s8, "NRRD field 'spacings' '1 nan 1'"},
        {"both.nrrd", nrrdHeader(f() + "spacings: 1 1 1\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n") + s8, "not both"},
        {"none.nrrd", nrrdHeader(f() + "space directions: (1,0,0) (0,1,0) none\n") + s8, "('none') is not a spatial axis"},
        {"singular.nrrd", nrrdHeader(f() + "space directions: (1,0,0) (2,0,0) (0,0,1)\n") + s8, "the direction matrix is singular"},
        {"infdir.nrrd", nrrdHeader(f() + "space directions: (1,0,0) (0,inf,0) (0,0,1)\n") + s8, "NRRD field 'space directions'"},
        {"origin.nrrd", nrrdHeader(f() + "space origin: (1,2)\n") + s8, "NRRD field 'space origin' '(1,2)'"},
        {"space4.nrrd", nrrdHeader(f() + "space: right-anterior-superior-time\n") + s8, "NRRD field 'space'"},
        {"unended.nrrd", "NRRD0004\n" + f(), "is not ended by a blank line"},
        {"bigheader.nrrd", bigHeader, "NRRD header does not end within 1048576 bytes"},
        {"skipgz.nrrd", nrrdHeader(nrrdFields("uchar", kDims, "little", "gzip") + "byte skip: -1\n") + s8, "only with raw encoding"},
        {"lineskip.nrrd", nrrdHeader(f() + "line skip: 1000\n") + s8, "the data file ends after"},
        {"badskip.nrrd", nrrdHeader(f() + "byte skip: -2\n") + s8, "NRRD field 'byte skip' '-2'"},
        {"nodata.nhdr", nrrdHeader(f() + "data file: missing.raw\n", false), "nodata.nhdr: its data file '"},
        {"gziplie.nrrd", nrrdHeader(nrrdFields("short", Coord(1024, 1024, 1024), "little", "gzip")) + gzipBytes(std::string(120, '\2')),
         "bytes of gzip data after its"},
        {"gzipcut.nrrd", nrrdHeader(nrrdFields("short", kDims, "little", "gzip")) + gzipBytes(std::string(120, '\2')).substr(0, 12),
         "gzip data"},
    };
}

std::vector<BadFile> badNpys() {
    const std::string data(120, '\1');
    const auto npy = [&](const std::string& dict) { return npyFile(dict, data); };
    std::string longHeader("\x93NUMPY\x02\x00\xff\xff\xff\x7f", 12);
    std::string cut = npy(npyDict("<i2", false, "(3, 4, 5)")).substr(0, 30);
    return {
        {"magic.npy", "NUMPY" + data, "not a NumPy .npy file"},
        {"version.npy", std::string("\x93NUMPY\x04\x00\x10\x00", 10) + data, "NumPy format version 4.0 is not supported"},
        {"long.npy", longHeader + data, "NumPy header length 2147483647 is more than weft accepts"},
        {"cut.npy", cut, "is cut short"},
        {"i8.npy", npy(npyDict("<i8", false, "(3, 4, 5)")), "NumPy header 'descr' '<i8'"},
        {"complex.npy", npy(npyDict("<c8", false, "(3, 4, 5)")), "NumPy header 'descr' '<c8'"},
        {"bar.npy", npy(npyDict("|i2", false, "(3, 4, 5)")), "NumPy header 'descr' '|i2'"},
        {"struct.npy", npy("{'descr': [('a', '<i4')], 'fortran_order': False, 'shape': (3, 4, 5)}"), "structured dtypes"},
        {"2d.npy", npy(npyDict("<i2", false, "(12, 5)")), "weft reads 3-D arrays"},
        {"zero.npy", npy(npyDict("<i2", false, "(0, 4, 5)")), "axis 0 of 0 elements"},
        {"huge.npy", npy(npyDict("<i2", false, "(99999999999, 4, 5)")), "axis 0 of 99999999999 elements"},
        {"digits.npy", npy(npyDict("<i2", false, "(999999999999999999999999, 4, 5)")), "expected a non-negative integer"},
        {"fortran.npy", npy("{'descr': '<i2', 'fortran_order': 'yes', 'shape': (3, 4, 5)}"), "'fortran_order' is not True or False"},
        {"key.npy", npy("{'descr': '<i2', 'fortran_order': False, 'shape': (3, 4, 5), 'x': True}"), "key 'x' is not one of"},
        {"missing.npy", npy("{'descr': '<i2', 'fortran_order': False}"), "has no 'shape'"},
        {"after.npy", npy("{'descr': '<i2', 'fortran_order': False, 'shape': (3, 4, 5)} junk"), "text after the closing"},
        {"string.npy", npy("{'descr: '<i2'}"), "NumPy header dict"},
        {"nested.npy", npy("{'descr': '<i2', 'fortran_order': False, 'shape': ((3, 4), 5)}"), "expected a non-negative integer"},
        {"short.npy", npyFile(npyDict("<i2", false, "(3, 4, 5)"), data.substr(0, 100)), "holds 100 bytes after its"},
        {"long2.npy", npyFile(npyDict("<i2", false, "(3, 4, 5)"), data + "x"), "holds 121 bytes after its"},
        {"nan.npy", npyFile(npyDict("<f4", false, "(1, 1, 2)"), std::string("\0\0\xc0\x7f\0\0\0\0", 8)), "voxel (0,0,0) holds nan"},
    };
}

std::vector<BadFile> badVtks() {
    const std::string data(60, '\1');
    const std::string head = "# vtk DataFile Version 3.0\nt\nBINARY\n";
    const std::string pad(130, ' ');  // room for 60 text samples: past the size bound, to the sample that is wrong
    return {
        {"not.vtk", "hello\n" + data, "not a VTK legacy file"},
        {"format.vtk", "# vtk DataFile Version 3.0\nt\nXML\n", "VTK 'XML': expected ASCII or BINARY"},
        {"poly.vtk", head + "DATASET POLYDATA\n", "VTK 'POLYDATA': weft reads DATASET STRUCTURED_POINTS"},
        {"cells.vtk", head + "DATASET STRUCTURED_POINTS\nDIMENSIONS 5 4 3\nCELL_DATA 24\n", "VTK 'CELL_DATA': cell data"},
        {"field.vtk", head + "DATASET STRUCTURED_POINTS\nFIELD FieldData 1\n", "VTK 'FIELD': field data"},
        {"vectors.vtk", head + "DATASET STRUCTURED_POINTS\nDIMENSIONS 5 4 3\nPOINT_DATA 60\nVECTORS v float\n" + data,
         "VTK 'VECTORS': attribute not supported"},
        {"comps.vtk", head + "DATASET STRUCTURED_POINTS\nDIMENSIONS 5 4 3\nPOINT_DATA 60\nSCALARS s float 3\n" + data,
         "weft reads one component"},
        {"long.vtk", vtkHeader("BINARY", kDims, "long") + data, "VTK 'long': sample type not supported"},
        {"dims.vtk", head + "DATASET STRUCTURED_POINTS\nDIMENSIONS 5 0 3\n", "VTK 'DIMENSIONS': expected 3 sizes"},
        {"count.vtk", head + "DATASET STRUCTURED_POINTS\nDIMENSIONS 5 4 3\nPOINT_DATA 61\n", "expected the point count 60"},
        {"spacing.vtk", vtkHeader("BINARY", kDims, "short", "SPACING 1 -1 1\n") + data, "VTK 'SPACING': expected 3 positive"},
        {"twice.vtk", vtkHeader("BINARY", kDims, "short", "ORIGIN 0 0 0\nORIGIN 1 1 1\n") + data, "VTK 'ORIGIN': given twice"},
        {"ends.vtk", head + "DATASET STRUCTURED_POINTS\nDIMENSIONS 5 4 3\n", "VTK header ends before its SCALARS array"},
        {"short.vtk", vtkHeader("BINARY", kDims, "short") + data, "short.vtk: holds 60 bytes after its"},
        {"word.vtk", vtkHeader("ASCII", kDims, "float") + "1 2 abc" + pad, "voxel (2,0,0) holds 'abc', not a finite f32 sample"},
        {"range.vtk", vtkHeader("ASCII", kDims, "unsigned_char") + "1 300" + pad, "voxel (1,0,0) holds '300', not a finite u8 sample"},
        {"few.vtk", vtkHeader("ASCII", kDims, "short") + "1 2 3" + pad, "holds 3 samples but the header's 5x4x3 i16 needs 60"},
        {"longword.vtk", vtkHeader("ASCII", kDims, "double") + std::string(100, '1') + pad, "a sample of more than 64 characters"},
        {"textlie.vtk", vtkHeader("ASCII", Coord(1024, 1024, 1024), "float") + "1 2 3\n", "too few for the 1073741824 text samples"},
        {"xml.vti", "<VTKFile type=\"ImageData\">", "VTK XML image data (.vti) is not supported"},
    };
}

// The process's peak resident memory so far.
long peakResidentKiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss;
}

void expectRejected(const std::vector<BadFile>& files) {
    TempDir dir;
    for (const BadFile& b : files) {
        writeBinary(dir / b.name, b.bytes);
        const long peakBefore = peakResidentKiB();
        const std::string msg = importError(dir / b.name);
        EXPECT_NE(msg.find(b.message), std::string::npos) << b.name << ": " << msg;
        EXPECT_NE(msg.find(b.name), std::string::npos) << "the message names the file: " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        // Rejected before the samples its header claims (up to gigabytes) are allocated.
        EXPECT_LT(peakResidentKiB() - peakBefore, 256 * 1024) << b.name;
    }
}

TEST(VolumeImportHostile, NrrdHeaders) { expectRejected(badNrrds()); }
TEST(VolumeImportHostile, NpyHeaders) { expectRejected(badNpys()); }
TEST(VolumeImportHostile, VtkHeaders) { expectRejected(badVtks()); }

// The parsers are functions of bytes: every prefix of a valid header is
// rejected or accepted without reading past its end (a fuzz target's view).
TEST(VolumeImportHostile, EveryPrefixOfAHeaderIsHandled) {
    const std::string nrrd = nrrdHeader(nrrdFields("short", kDims) + "space directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (1,2,3)\n");
    const std::string npy = npyFile(npyDict("<i2", false, "(3, 4, 5)"), "");
    const std::string vtk = vtkHeader("BINARY", kDims, "short");
    for (std::size_t n = 0; n <= nrrd.size(); ++n) errorOf([&] { parseNrrdHeader(std::string_view(nrrd).substr(0, n), true, "p"); });
    for (std::size_t n = 0; n <= npy.size(); ++n) errorOf([&] { parseNpyHeader(std::string_view(npy).substr(0, n), "p"); });
    for (std::size_t n = 0; n <= vtk.size(); ++n) errorOf([&] { parseVtkImageHeader(std::string_view(vtk).substr(0, n), true, "p"); });
    EXPECT_EQ(parseNrrdHeader(nrrd, true, "p").volume.dataOffset, nrrd.size());
    EXPECT_EQ(parseNpyHeader(npy, "p").dataOffset, npy.size());
    EXPECT_EQ(parseVtkImageHeader(vtk, true, "p").dataOffset, vtk.size());
    EXPECT_NE(errorOf([&] { parseNpyHeader(std::string_view(npy).substr(0, npy.size() - 1), "p"); }).find("cut short"), std::string::npos);
}
