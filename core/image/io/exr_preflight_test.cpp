// The EXR header check refuses corrupt sizes before OpenEXR allocates them,
// and passes every file weft writes.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "core/image/io/exr_preflight.hpp"
#include "core/image/io/image_io.hpp"
#include "tests/support/test_support.hpp"

namespace weft {
namespace {

std::string written(const test::TempDir& dir, const ImageWindow* window = nullptr) {
    Image img(8, 4, {"R", "G", "B", "A"});
    const std::string path = (dir / "a.exr").string();
    if (window) writeExr(img, path, {{"weft:technique", "volume.raymarch"}}, *window);
    else writeExr(img, path, {{"weft:technique", "volume.raymarch"}});
    return test::readBytes(path);
}

std::string preflightError(const test::TempDir& dir, const std::string& bytes) {
    const auto path = dir / "b.exr";
    test::writeText(path, bytes);
    return test::errorOf([&] { preflightExr(path.string()); });
}

// Overwrites the 4-byte little-endian word at `at`.
void putWord(std::string& bytes, std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes[at + i] = char((v >> (8 * i)) & 0xff);
}

TEST(ExrPreflight, PassesWhatWeftWrites) {
    test::TempDir dir;
    EXPECT_EQ(preflightError(dir, written(dir)), "");
    const ImageWindow tile{0, 2, 8, 8};
    EXPECT_EQ(preflightError(dir, written(dir, &tile)), "");
}

TEST(ExrPreflight, ReportsWhatTheHeaderDeclares) {
    test::TempDir dir;
    const auto path = dir / "c.exr";
    writeExr(Image(8, 4, {"R", "G", "B", "A", "N.X", "N.Y", "N.Z"}), path.string(), {}, ImageWindow{0, 1, 8, 6});
    const ExrDeclared d = preflightExr(path.string());
    EXPECT_EQ(d.dataPixels, 32u);
    EXPECT_EQ(d.displayPixels, 48u);
    EXPECT_EQ(d.pixelValues, 32u * 7);
}

// OpenEXR reads a channel list up to its empty name and a box2i as 16 bytes,
// whatever size the attribute states: a different size would hide part of
// the header from this walk (a fuzzed file hid a 2359300-pixel dataWindow so).
TEST(ExrPreflight, RefusesAttributeSizesOpenExrWouldReadOtherwise) {
    test::TempDir dir;
    const std::string good = written(dir);
    std::string bad = good;
    const std::size_t chlist = bad.find(std::string("channels\0chlist\0", 16));
    ASSERT_NE(chlist, std::string::npos);
    putWord(bad, chlist + 16, std::uint8_t(bad[chlist + 16]) + 18u);
    EXPECT_NE(preflightError(dir, bad).find("the channel list does not end where its attribute's"), std::string::npos);
    bad = good;
    const std::size_t window = bad.find(std::string("dataWindow\0box2i\0", 17));
    ASSERT_NE(window, std::string::npos);
    putWord(bad, window + 17, 20);
    EXPECT_NE(preflightError(dir, bad).find("type 'box2i' holds 20 bytes instead of 16"), std::string::npos)
        << preflightError(dir, bad);
    // A size that ends one byte into the next channel's name: that byte is no
    // terminator (a fuzzed file's list so ran 67 bytes on, and OpenEXR then
    // read an attribute size of 825 MB out of the pixels' offsets).
    bad = good;
    putWord(bad, chlist + 16, 18 + 1);
    EXPECT_NE(preflightError(dir, bad).find("the channel list does not end where its attribute's 19 bytes end"),
              std::string::npos) << preflightError(dir, bad);
    // A stringvector's strings must fit in it: OpenEXR reads each length and allocates it.
    const auto word = [](std::uint32_t v) {
        std::string w(4, '\0');
        putWord(w, 0, v);
        return w;
    };
    const auto withStrings = [&](std::uint32_t size, const std::string& body) {
        std::string attr = std::string("names\0stringvector\0", 19) + word(size) + body;
        attr.resize(23 + size, 'x');
        return good.substr(0, 8) + attr + good.substr(8);
    };
    EXPECT_EQ(preflightError(dir, withStrings(4 + 3 + 4, word(3) + "abc" + word(0))), "");
    EXPECT_NE(preflightError(dir, withStrings(8, word(0x7fffffff))).find("a stringvector string of 2147483647 bytes in the 4 left"),
              std::string::npos);
    EXPECT_NE(preflightError(dir, withStrings(6, word(1))).find("ends inside a length"), std::string::npos);
    // A preview attribute (OpenEXR allocates its width x height pixels) must hold exactly them,
    // also where width x height x 4 would wrap around 2^64.
    const auto withPreview = [&](std::uint32_t w, std::uint32_t h, std::uint32_t pixelBytes) {
        std::string attr = std::string("preview\0preview\0", 16) + std::string(4 + 8 + pixelBytes, '\0');
        putWord(attr, 16, 8 + pixelBytes), putWord(attr, 20, w), putWord(attr, 24, h);
        return good.substr(0, 8) + attr + good.substr(8);
    };
    EXPECT_EQ(preflightError(dir, withPreview(1, 1, 4)), "");
    EXPECT_NE(preflightError(dir, withPreview(2, 1, 4)).find("a preview image of 2x1 in 12 bytes"), std::string::npos);
    // 2^31 x 2^31 x 4 bytes is 2^64, which wraps to the 0 bytes this one holds.
    EXPECT_NE(preflightError(dir, withPreview(1u << 31, 1u << 31, 0)).find("a preview image of 2147483648x2147483648"),
              std::string::npos);
}

TEST(ExrPreflight, RefusesSizesTheFileCannotHold) {
    test::TempDir dir;
    const std::string good = written(dir);
    // A string attribute claiming 2 GB.
    std::string bad = good;
    const std::size_t at = bad.find(std::string("weft:technique\0string\0", 22));
    ASSERT_NE(at, std::string::npos);
    putWord(bad, at + 22, 0x7fffffff);
    const std::string e = preflightError(dir, bad);
    EXPECT_NE(e.find("attribute 'weft:technique' ('string') claims 2147483647 bytes"), std::string::npos) << e;
    // A data window of 2^30 lines: an offset table of 8 GB.
    bad = good;
    const std::size_t window = bad.find(std::string("dataWindow\0box2i\0", 17));
    ASSERT_NE(window, std::string::npos);
    putWord(bad, window + 17 + 4 + 12, 1u << 30);  // yMax
    EXPECT_NE(preflightError(dir, bad).find("offset table of"), std::string::npos);
    // Cut inside the header, and not an EXR at all.
    EXPECT_NE(preflightError(dir, good.substr(0, 40)).find("cut short"), std::string::npos);
    EXPECT_NE(preflightError(dir, good.substr(0, 10)).find("ends inside its header"), std::string::npos);
    EXPECT_NE(preflightError(dir, "P6\n8 4\n255\n").find("cannot be read: not an EXR file"), std::string::npos);
    // readImage runs the check.
    test::writeText(dir / "c.exr", good.substr(0, 40));
    EXPECT_NE(test::errorOf([&] { readImage((dir / "c.exr").string()); }).find("cut short"), std::string::npos);
}

}  // namespace
}  // namespace weft
