// The walk over a .vdb file's lengths and counts: a whole file passes, and
// each corruption that made OpenVDB allocate gigabytes or loop for minutes
// is named as the field it is.
#include "core/volume/vdb_preflight.hpp"

#include <gtest/gtest.h>

#include <openvdb/io/File.h>

#include <cstring>

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

// The walk covers format versions 213 to the library's own; OpenVDB's
// readers of other versions trust lengths it cannot check.
TEST_F(VdbPreflight, FormatVersionsOutsideTheWalkAreRefused) {
    for (const std::uint32_t version : {0u, 212u, openvdb::OPENVDB_FILE_VERSION + 1, 0xffffffffu}) {
        std::string b = bytes;
        put32(b, 8, version);
        EXPECT_NE(verdict(b).find("file format version " + std::to_string(version) + " is not one weft reads"),
                  std::string::npos) << version;
    }
    for (const std::uint32_t version : {213u, openvdb::OPENVDB_FILE_VERSION}) {
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

TEST_F(VdbPreflight, EveryCutIsEitherCleanOrNamed) {
    // A file cut anywhere: the walk never reads past the end (an Error or a pass).
    for (std::size_t n = 0; n < bytes.size(); n += 37) {
        const std::string v = verdict(bytes.substr(0, n));
        if (!v.empty()) EXPECT_TRUE(v.find("corrupt file (") != std::string::npos || v.find("the file is cut short") != std::string::npos) << v;
    }
}

}  // namespace
}  // namespace weft
