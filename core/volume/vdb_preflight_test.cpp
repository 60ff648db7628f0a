// The walk over a .vdb file's lengths and counts: a whole file passes, and
// each corruption that made OpenVDB allocate gigabytes or loop for minutes
// is named as the field it is.
#include "core/volume/io/vdb_preflight.hpp"

#include <gtest/gtest.h>

#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <fstream>

#include <cstring>

#include "core/volume/io/vdb_leaf_reader.hpp"
#include "core/volume/volume.hpp"

#include "core/base/error.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/vdb_fixtures.hpp"

namespace weft {
namespace {

class VdbPreflight : public ::testing::Test {
protected:
    void SetUp() override {
        test::writeProceduralVdb(dir / "cloud.vdb", "cloud", 32);
        bytes = test::readBytes(dir / "cloud.vdb");
    }
    // The message of the walk over `b`, "" when it passes.
    static std::string verdict(const std::string& b) {
        try {
            preflightVdbBytes(b, "v.vdb");
            return "";
        } catch (const Error& e) {
            return e.what();
        }
    }
    // Offset of the 32-bit length just before the first occurrence of `text`.
    std::size_t lengthBefore(const std::string& text) const {
        const std::size_t at = bytes.find(text);
        EXPECT_NE(at, std::string::npos) << text;
        return at - 4;
    }
    static void put32(std::string& b, std::size_t at, std::uint32_t v) { std::memcpy(&b[at], &v, 4); }

    test::TempDir dir;
    std::string bytes;
};

TEST_F(VdbPreflight, AWholeFilePasses) { EXPECT_EQ(verdict(bytes), ""); }

TEST_F(VdbPreflight, SeveralGridsOfOtherTypesAndHalfFloatsPass) {
    initVdb();
    auto density = makeProceduralGrid("sphere", 16, 1);
    density->setName("density");
    density->setSaveFloatAsHalf(true);
    auto velocity = openvdb::Vec3SGrid::create(openvdb::Vec3s(0));
    velocity->setName("vel");
    velocity->setTransform(openvdb::math::Transform::createLinearTransform(openvdb::math::Mat4d(
        0.5, 0.1, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.7, 0.0, 1.0, 2.0, 3.0, 1.0)));
    velocity->tree().setValue(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1, 0, 0));
    auto flags = openvdb::BoolGrid::create(false);
    flags->setName("mask");
    flags->tree().setValue(openvdb::Coord(0), true);
    openvdb::io::File file((dir / "many.vdb").string());
    file.write({density, velocity, flags});
    file.close();
    EXPECT_EQ(verdict(test::readBytes(dir / "many.vdb")), "");
}

TEST_F(VdbPreflight, NotAVdbIsLeftToOpenVdb) {
    EXPECT_EQ(verdict("this is not a vdb file"), "");
    EXPECT_EQ(verdict(""), "");
}

// The walk covers format versions 220 to the library's own; OpenVDB's
// readers of other versions trust lengths it cannot check.
TEST_F(VdbPreflight, FormatVersionsOutsideTheWalkAreRefused) {
    for (const std::uint32_t version : {0u, 219u, openvdb::OPENVDB_FILE_VERSION + 1, 0xffffffffu}) {
        std::string b = bytes;
        put32(b, 8, version);
        EXPECT_NE(verdict(b).find("file format version " + std::to_string(version) + " is not one weft reads"),
                  std::string::npos) << version;
    }
    for (const std::uint32_t version : {220u, openvdb::OPENVDB_FILE_VERSION}) {
        std::string b = bytes;
        put32(b, 8, version);
        EXPECT_EQ(verdict(b).find("is not one weft reads"), std::string::npos) << version;
    }
}

TEST_F(VdbPreflight, HugeGridNameLength) {
    std::string b = bytes;
    put32(b, lengthBefore("Tree_float"), 0xffffff0d);
    const std::string v = verdict(b);
    EXPECT_NE(v.find("volume 'v.vdb': corrupt file (grid type claims 4294967053 bytes at byte"), std::string::npos) << v;
}

TEST_F(VdbPreflight, HugeMetadataValueSize) {
    std::string b = bytes;
    // "class" / "string" / <size> "fog volume": the value's size follows the type name.
    const std::size_t at = b.find("fog volume");
    ASSERT_NE(at, std::string::npos);
    put32(b, at - 4, 0x7fffffff);
    const std::string v = verdict(b);
    EXPECT_NE(v.find("metadata value of 2147483647 bytes runs past the end of the file"), std::string::npos) << v;
}

TEST_F(VdbPreflight, RootChildCountBeyondTheTopology) {
    // The root's counts follow the transform: its type name, then its data.
    const std::pair<const char*, std::size_t> maps[] = {
        {"UniformScaleTranslateMap", 6 * 24}, {"ScaleTranslateMap", 6 * 24}, {"UniformScaleMap", 5 * 24},
        {"ScaleMap", 5 * 24}, {"AffineMap", 128}, {"TranslationMap", 24}};
    std::size_t mapEnd = std::string::npos, dataBytes = 0;
    for (const auto& [name, size] : maps) {
        const std::size_t at = bytes.find(std::string(name));
        std::uint32_t length = 0;
        if (at == std::string::npos || at < 4) continue;
        std::memcpy(&length, &bytes[at - 4], 4);
        if (length != std::strlen(name)) continue;  // a suffix of a longer name
        mapEnd = at + length, dataBytes = size;
        break;
    }
    ASSERT_NE(mapEnd, std::string::npos);
    const std::size_t children = mapEnd + dataBytes + 4 + 4 + 4;  // map data, buffer count, background, tile count
    std::string b = bytes;
    put32(b, children, 0xfffffff0);
    const std::string v = verdict(b);
    EXPECT_NE(v.find("children do not fit in the"), std::string::npos) << v;
}

TEST_F(VdbPreflight, GridPositionsOutsideTheFile) {
    std::string b = bytes;
    // The descriptor's three positions follow the empty instance-parent name after the grid type.
    const std::size_t type = b.find("Tree_float");
    const std::size_t afterType = b.find('\0', type);  // the instance parent's length (0) starts with a zero byte
    const std::size_t positions = afterType + 4;
    std::string cut = b;
    const std::int64_t far = std::int64_t(1) << 40, negative = -5;
    std::memcpy(&cut[positions + 16], &far, 8);  // end position beyond the file: a cut file
    EXPECT_NE(verdict(cut).find("the file is cut short (grid 1 ends at byte 1099511627776"), std::string::npos) << verdict(cut);
    std::memcpy(&b[positions], &negative, 8);  // grid position before the file: corrupt
    const std::string v = verdict(b);
    EXPECT_NE(v.find("grid positions -5, "), std::string::npos) << v;
}

// OpenVDB reads a fixed-size value at its own size whatever size the file
// states; a bool must be 0 or 1.
TEST_F(VdbPreflight, FixedSizeMetadataMustHaveItsSizeAndBoolsBeBools) {
    initVdb();
    auto grid = makeProceduralGrid("sphere", 16, 1);
    grid->setName("density");
    grid->insertMeta("frame", openvdb::Int32Metadata(7));
    grid->insertMeta("cached", openvdb::BoolMetadata(true));
    openvdb::io::File file((dir / "meta.vdb").string());
    file.write({grid});
    file.close();
    const std::string b = test::readBytes(dir / "meta.vdb");
    ASSERT_EQ(verdict(b), "");
    // name "frame", type "int32", then the size 4 and the value.
    const std::size_t frame = b.find("int32", b.find("frame")) + 5;
    std::string wider = b;
    put32(wider, frame, 8);
    EXPECT_NE(verdict(wider).find("int32 metadata stating 8 bytes where OpenVDB reads 4"), std::string::npos) << verdict(wider);
    const std::size_t cached = b.find("bool", b.find("cached")) + 4;
    std::string two = b;
    two[cached + 4] = 2;
    EXPECT_NE(verdict(two).find("bool metadata 2 (not 0 or 1)"), std::string::npos) << verdict(two);
}

TEST_F(VdbPreflight, EveryCutIsEitherCleanOrNamed) {
    // A file cut anywhere: the walk never reads past the end (an Error or a pass).
    for (std::size_t n = 0; n < bytes.size(); n += 37) {
        const std::string v = verdict(bytes.substr(0, n));
        if (!v.empty()) {
            EXPECT_TRUE(v.find("corrupt file (") != std::string::npos || v.find("the file is cut short") != std::string::npos) << v;
        }
    }
}

}  // namespace
}  // namespace weft

namespace weft {
namespace {

// ---- the walk over a float tree's nodes and chunks ---------------------------

// A grid with every kind of node record: leaves with inactive voxels of one,
// two and more values, active and inactive tiles in internal nodes and at
// the root, and a narrow-band level set's +-background.
std::vector<openvdb::FloatGrid::Ptr> gridsOfEveryRecord() {
    initVdb();
    auto fog = makeProceduralGrid("sphere", 24, 1);
    fog->setName("density");
    fog->tree().setValueOff(openvdb::Coord(0, 0, 0), 0.25f);             // one inactive non-background value
    fog->tree().setValueOff(openvdb::Coord(1, 0, 0), 0.5f);              // and a second
    fog->tree().fill(openvdb::CoordBBox({64, 64, 64}, {191, 191, 191}), 0.75f, true);  // 128^3 internal-node tiles
    fog->tree().addTile(3, openvdb::Coord(8192, 0, 0), 0.5f, false);   // a root tile
    auto level = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(10.0f, openvdb::Vec3f(0), 0.5f, 3.0f);
    level->setName("surface");
    return {fog, level};
}

std::string writeWith(const std::filesystem::path& path, std::vector<openvdb::FloatGrid::Ptr> grids, std::uint32_t compression,
                      bool half) {
    openvdb::GridPtrVec all;
    for (auto& g : grids) {
        g->setSaveFloatAsHalf(half);
        all.push_back(g);
    }
    openvdb::io::File file(path.string());
    file.setCompression(compression);
    file.write(all);
    file.close();
    return test::readBytes(path);
}

// OpenVDB's own read of a grid, every leaf loaded as it loads them.
template <class GridT>
typename GridT::Ptr readByOpenVdb(const std::filesystem::path& path, const std::string& name) {
    openvdb::io::File file(path.string());
    file.open(false);
    return openvdb::gridPtrCast<GridT>(file.readGrid(name));
}

// The same topology and the same bits in every voxel (NaNs included) and tile.
template <class GridT>
void expectSameTree(const GridT& got, const GridT& want) {
    ASSERT_EQ(got.tree().leafCount(), want.tree().leafCount());
    EXPECT_EQ(got.tree().activeVoxelCount(), want.tree().activeVoxelCount());
    EXPECT_EQ(got.tree().activeTileCount(), want.tree().activeTileCount());
    int differing = 0;
    for (auto leaf = want.tree().cbeginLeaf(); leaf; ++leaf) {
        const auto* other = got.tree().probeConstLeaf(leaf->origin());
        ASSERT_NE(other, nullptr) << leaf->origin();
        EXPECT_TRUE(other->getValueMask() == leaf->getValueMask()) << leaf->origin();
        differing += std::memcmp(other->buffer().data(), leaf->buffer().data(), sizeof(typename GridT::ValueType) * 512) != 0;
    }
    EXPECT_EQ(differing, 0);
    for (auto tile = want.tree().cbeginValueAll(); tile; ++tile)
        if (!tile.isVoxelValue()) {
            EXPECT_EQ(got.tree().getValue(tile.getCoord()), *tile) << tile.getCoord();
            EXPECT_EQ(got.tree().isValueOn(tile.getCoord()), tile.isValueOn()) << tile.getCoord();
        }
}

// weft decodes the leaves itself where the walk found them
// (vdb_leaf_reader.hpp): the grids equal OpenVDB's own read of the file.
TEST_F(VdbPreflight, FloatTreesOfEveryCompressionPassAndRead) {
    const auto grids = gridsOfEveryRecord();
    const std::uint32_t mask = openvdb::io::COMPRESS_ACTIVE_MASK, blosc = openvdb::io::COMPRESS_BLOSC,
                        zip = openvdb::io::COMPRESS_ZIP;
    for (const std::uint32_t compression : {0u, mask, zip, zip | mask, blosc, blosc | mask})
        for (const bool half : {false, true}) {
            SCOPED_TRACE(std::to_string(compression) + (half ? " half" : ""));
            const auto path = dir / ("c" + std::to_string(compression) + (half ? "h" : "") + ".vdb");
            EXPECT_EQ(verdict(writeWith(path, grids, compression, half)), "");
            for (const char* name : {"density", "surface"})
                expectSameTree(*readFloatGrid(path.string(), name), *readByOpenVdb<openvdb::FloatGrid>(path, name));
        }
}

// A grid opened with delayed loading, as weft opens it, with the walk's layout.
struct DelayLoaded {
    openvdb::GridBase::Ptr grid;
    std::shared_ptr<const VdbLayout> layout;
};
DelayLoaded openDelayLoaded(const std::filesystem::path& path, const std::string& name) {
    DelayLoaded d;
    d.layout = preflightVdb(path.string());
    openvdb::io::File file(path.string());
    file.setCopyMaxBytes(0);
    file.open(true);
    d.grid = file.readGrid(name);
    return d;
}

// Every leaf is decoded from the mapped file. A grid the layout cannot place
// leaf by leaf (a leaf moved, the file changed size since its walk, two
// grids of one name) is refused: OpenVDB's own delayed load would read a
// corrupt file's raw chunk past its buffer.
TEST_F(VdbPreflight, LeavesAreDecodedWhereTheWalkFoundThemAndAGridItCannotPlaceIsRefused) {
    const auto path = dir / "leaves.vdb";
    writeWith(path, gridsOfEveryRecord(), openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK, false);
    const auto want = readByOpenVdb<openvdb::FloatGrid>(path, "density");
    const std::size_t leaves = want->tree().leafCount();
    ASSERT_GT(leaves, 10u);
    {
        DelayLoaded d = openDelayLoaded(path, "density");
        EXPECT_EQ(loadLeaves(d.grid, path.string(), d.layout.get(), &d.layout->grids.at("density")), leaves);
        expectSameTree(*openvdb::gridPtrCast<openvdb::FloatGrid>(d.grid), *want);
    }
    {
        DelayLoaded d = openDelayLoaded(path, "density");
        VdbGridLayout moved = d.layout->grids.at("density");
        moved.leaves[3].origin[0] += 8;
        EXPECT_EQ(test::errorOf([&] { loadLeaves(d.grid, path.string(), d.layout.get(), &moved); }),
                  "leaf 3 is not where the file's buffers place it");
    }
    {
        DelayLoaded d = openDelayLoaded(path, "density");
        VdbLayout resized = *d.layout;
        resized.fileSize += 1;
        EXPECT_EQ(test::errorOf([&] { loadLeaves(d.grid, path.string(), &resized, &resized.grids.at("density")); }),
                  "the file changed while it was read");
    }
}

// Two grids stored under one name (edited into the file: OpenVDB writes
// unique names) keep no layout, and which one to read is nobody's guess: refused.
TEST_F(VdbPreflight, GridsSharingANameAreRefused) {
    auto grids = gridsOfEveryRecord();
    grids[0]->setName("gridA"), grids[1]->setName("gridB");
    const auto path = dir / "twins.vdb";
    std::string b = writeWith(path, grids, openvdb::io::COMPRESS_BLOSC, false);
    for (std::size_t at = b.find("gridB"); at != std::string::npos; at = b.find("gridB", at)) b[at + 4] = 'A';
    std::ofstream(path, std::ios::binary) << b;
    const VdbLayout layout = preflightVdbBytes(b, "twins.vdb");
    ASSERT_EQ(layout.grids.count("gridA"), 1u);
    EXPECT_FALSE(layout.grids.at("gridA").unique);
    EXPECT_TRUE(layout.grids.at("gridA").leaves.empty());
    EXPECT_NE(test::errorOf([&] { readFloatGrid(path.string(), "gridA"); }).find("two grids of the file have its name"), std::string::npos);
}

// The walk records every leaf buffer with its origin, in the tree's own leaf order.
TEST_F(VdbPreflight, TheLayoutPlacesEveryLeaf) {
    const auto grids = gridsOfEveryRecord();
    const VdbLayout layout = preflightVdbBytes(writeWith(dir / "layout.vdb", grids, openvdb::io::COMPRESS_BLOSC, false), "layout.vdb");
    EXPECT_EQ(layout.fileSize, test::readBytes(dir / "layout.vdb").size());
    for (std::size_t g = 0; g < grids.size(); ++g) {
        const auto it = layout.grids.find(grids[g]->getName());
        ASSERT_NE(it, layout.grids.end()) << grids[g]->getName();
        const auto& leaves = it->second.leaves;
        ASSERT_EQ(leaves.size(), grids[g]->tree().leafCount());
        std::size_t i = 0;
        for (auto leaf = grids[g]->tree().cbeginLeaf(); leaf; ++leaf, ++i) {
            EXPECT_EQ(openvdb::Coord(leaves[i].origin[0], leaves[i].origin[1], leaves[i].origin[2]), leaf->origin()) << i;
            if (i > 0) EXPECT_GT(leaves[i].pos, leaves[i - 1].pos);
        }
    }
}

// One leaf of incompressible values, so zip stores its chunk as is.
openvdb::FloatGrid::Ptr leafOfNoise() {
    initVdb();
    auto grid = openvdb::FloatGrid::create(0.0f);
    std::uint32_t state = 12345;
    for (int i = 0; i < 512; ++i) {
        state = state * 1664525u + 1013904223u;
        float value;  // random bits: NaNs too, which a file stores like any value
        std::memcpy(&value, &state, 4);
        grid->tree().setValue(openvdb::Coord(i & 7, (i >> 3) & 7, i >> 6), value);
    }
    grid->setName("density");
    return grid;
}

TEST_F(VdbPreflight, UncompressedZipChunkOfAnotherSizeIsRefused) {
    std::string b = writeWith(dir / "zip.vdb", {leafOfNoise()}, openvdb::io::COMPRESS_ZIP, false);
    const std::int64_t stored = -2048, stated = -4096;  // the leaf's 512 floats
    const std::size_t at = b.rfind(std::string(reinterpret_cast<const char*>(&stored), 8));
    ASSERT_NE(at, std::string::npos);
    std::memcpy(&b[at], &stated, 8);
    const std::string v = verdict(b);
    EXPECT_NE(v.find("uncompressed zip chunk of 4096 bytes where the node's values take 2048 at byte"), std::string::npos) << v;
}

// Leaves are read in parallel from the mapped file after the walk: a chunk
// whose compressed bytes do not decode (the walk checks sizes, not
// contents) is a clean error, not a crash, and the next read works.
TEST_F(VdbPreflight, AChunkThatDoesNotDecodeIsACleanError) {
    initVdb();
    auto ramp = openvdb::FloatGrid::create(0.0f);  // repeating values: zip compresses every leaf
    ramp->setName("density");
    for (int i = 0; i < 4096; ++i) ramp->tree().setValue(openvdb::Coord(i & 15, (i >> 4) & 15, i >> 8), float(i % 7));
    std::string b = writeWith(dir / "zip.vdb", {ramp}, openvdb::io::COMPRESS_ZIP, false);
    std::size_t stream = 0;  // the last zlib stream (a deflate header of any level)
    for (const char* header : {"\x78\x01", "\x78\x5e", "\x78\x9c", "\x78\xda"})
        if (const std::size_t at = b.rfind(header); at != std::string::npos) stream = std::max(stream, at);
    ASSERT_GT(stream, 0u);
    ASSERT_LT(stream + 40, b.size());
    for (std::size_t i = stream + 2; i < stream + 40; ++i) b[i] = char(0xff);
    EXPECT_EQ(verdict(b), "");  // the sizes still hold
    const auto path = dir / "bad.vdb";
    std::ofstream(path, std::ios::binary) << b;
    try {
        readFloatGrid(path.string(), "density");
        ADD_FAILURE() << "a chunk that does not decode was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot be read: the file is corrupt"), std::string::npos) << e.what();
    }
    EXPECT_GT(readFloatGrid((dir / "zip.vdb").string(), "density")->activeVoxelCount(), 0);
}

TEST_F(VdbPreflight, BloscHeaderOfAnotherSizeIsRefused) {
    std::string b = writeWith(dir / "blosc.vdb", {leafOfNoise()}, openvdb::io::COMPRESS_BLOSC, false);
    // The leaf's chunk: its size, then blosc's header stating 2048 bytes decompressed and the size again.
    std::size_t header = std::string::npos;
    for (std::size_t i = 0; i + 24 <= b.size() && header == std::string::npos; ++i) {
        std::int64_t n;
        std::uint32_t decompressed, compressed;
        std::memcpy(&n, &b[i], 8);
        std::memcpy(&decompressed, &b[i + 12], 4);
        std::memcpy(&compressed, &b[i + 20], 4);
        if (n > 16 && decompressed == 2048 && compressed == std::uint64_t(n)) header = i + 8;
    }
    ASSERT_NE(header, std::string::npos);
    std::string wider = b;
    put32(wider, header + 4, 4096);
    const std::string v = verdict(wider);
    EXPECT_NE(v.find("compressed and 4096 decompressed where 2048 are expected"), std::string::npos) << v;
    put32(b, header + 12, 1u << 30);  // more compressed bytes than the chunk holds
    EXPECT_NE(verdict(b).find("compressed and 2048 decompressed"), std::string::npos) << verdict(b);
}

// Written as a stream, a file has no grid offsets and OpenVDB reads all of
// its grids to find one: float and vec3s grids are walked, others refused.
TEST_F(VdbPreflight, StreamedFilesAreWalkedGridByGrid) {
    const auto write = [&](const openvdb::GridPtrVec& grids) {
        {
            std::ofstream out((dir / "stream.vdb").string(), std::ios::binary);
            openvdb::io::Stream(out).write(grids);
        }
        return test::readBytes(dir / "stream.vdb");
    };
    const auto grids = gridsOfEveryRecord();
    EXPECT_EQ(verdict(write({grids[0], grids[1]})), "");
    EXPECT_EQ(readFloatGrid((dir / "stream.vdb").string(), "surface")->activeVoxelCount(), grids[1]->activeVoxelCount());
    auto velocity = openvdb::Vec3SGrid::create(openvdb::Vec3s(0));
    velocity->setName("vel");
    velocity->tree().setValue(openvdb::Coord(3, 4, 5), openvdb::Vec3s(1, 2, 3));
    velocity->tree().addTile(1, openvdb::Coord(128, 0, 0), openvdb::Vec3s(0, 1, 0), true);
    EXPECT_EQ(verdict(write({grids[0], velocity})), "");
    auto labels = openvdb::Int32Grid::create(0);
    labels->setName("labels");
    const std::string v = verdict(write({grids[0], labels}));
    EXPECT_NE(v.find("written as a stream (no grid offsets) and holds a Tree_int32_5_4_3 grid"), std::string::npos) << v;
}

// Vec3s trees (velocity, colour) are walked like float ones, three floats a
// value, full or half precision; a cut chunk is caught in them too.
TEST_F(VdbPreflight, Vec3sTreesAreWalked) {
    auto velocity = openvdb::Vec3SGrid::create(openvdb::Vec3s(0));
    velocity->setName("vel");
    for (int i = 0; i < 40; ++i) velocity->tree().setValue(openvdb::Coord(i * 3, i % 7, -i), openvdb::Vec3s(float(i), 1, -2));
    velocity->tree().addTile(2, openvdb::Coord(0, 1024, 0), openvdb::Vec3s(0, 1, 0), true);
    for (const bool half : {false, true}) {
        velocity->setSaveFloatAsHalf(half);
        openvdb::io::File file((dir / "vel.vdb").string());
        file.write({velocity});
        file.close();
        const std::string bytes = test::readBytes(dir / "vel.vdb");
        EXPECT_EQ(verdict(bytes), "") << (half ? "half" : "float");
        expectSameTree(*readVec3Grid((dir / "vel.vdb").string(), "vel", "velocity"), *readByOpenVdb<openvdb::Vec3SGrid>(dir / "vel.vdb", "vel"));
        EXPECT_NE(verdict(bytes.substr(0, bytes.size() - 40)), "") << "a cut file passed, " << (half ? "half" : "float");
    }
}

// Only float grids are handed to OpenVDB's tree reader.
TEST_F(VdbPreflight, AGridOfAnotherTypeIsRefusedBeforeItsTreeIsRead) {
    initVdb();
    auto velocity = openvdb::Vec3SGrid::create(openvdb::Vec3s(0));
    velocity->setName("density");
    velocity->tree().setValue(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1, 0, 0));
    openvdb::io::File file((dir / "vel.vdb").string());
    file.write({velocity});
    file.close();
    try {
        readFloatGrid((dir / "vel.vdb").string(), "density");
        ADD_FAILURE() << "a vec3s grid was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("holds vec3s values; weft renders float grids"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace weft
