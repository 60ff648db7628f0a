// PNG previews through libpng: the pixels read back as written, the file
// says sRGB and carries no time stamp (same pixels, same bytes), a preview
// does not load the OpenImageIO module, and a failed write says why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/base/rng.hpp"
#include "core/image/io/image_io.hpp"
#include "core/image/io/png_writer.hpp"
#include "tests/support/test_support.hpp"

namespace weft {
namespace {

std::vector<unsigned char> noiseBytes(int w, int h, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<unsigned char> bytes(std::size_t(w) * h * 3);
    for (auto& b : bytes) b = static_cast<unsigned char>(rng.uniform() * 256.0);
    return bytes;
}

// The chunk types of a PNG file, in order.
std::vector<std::string> chunkTypes(const std::string& file) {
    std::vector<std::string> types;
    for (std::size_t p = 8; p + 12 <= file.size();) {
        const auto byte = [&](std::size_t i) { return std::uint32_t(static_cast<unsigned char>(file[i])); };
        const std::uint32_t length = byte(p) << 24 | byte(p + 1) << 16 | byte(p + 2) << 8 | byte(p + 3);
        types.push_back(file.substr(p + 4, 4));
        p += 12 + length;
    }
    return types;
}

TEST(PngWriter, PixelsReadBackAsWritten) {
    test::TempDir dir;
    const int w = 37, h = 23;  // odd sizes: no row padding assumed
    const auto bytes = noiseBytes(w, h, 5);
    ASSERT_EQ(writePngRgb8((dir / "n.png").string(), w, h, bytes.data()), "");
    const Image back = readImage((dir / "n.png").string());
    ASSERT_EQ(back.width(), w);
    ASSERT_EQ(back.height(), h);
    ASSERT_EQ(back.channelCount(), 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_FLOAT_EQ(back.at(x, y, c), bytes[(std::size_t(y) * w + x) * 3 + c] / 255.0f) << x << "," << y;
}

TEST(PngWriter, SaysSrgbAndTheSamePixelsGiveTheSameBytes) {
    test::TempDir dir;
    const auto bytes = noiseBytes(16, 9, 6);
    ASSERT_EQ(writePngRgb8((dir / "a.png").string(), 16, 9, bytes.data()), "");
    ASSERT_EQ(writePngRgb8((dir / "b.png").string(), 16, 9, bytes.data()), "");
    const std::string a = test::readBytes(dir / "a.png");
    EXPECT_EQ(a, test::readBytes(dir / "b.png"));
    const auto types = chunkTypes(a);
    ASSERT_FALSE(types.empty());
    EXPECT_EQ(types.front(), "IHDR");
    EXPECT_EQ(types.back(), "IEND");
    EXPECT_NE(std::find(types.begin(), types.end(), "sRGB"), types.end());
    EXPECT_EQ(std::find(types.begin(), types.end(), "tIME"), types.end());
}

TEST(PngWriter, AFailedWriteSaysWhy) {
    test::TempDir dir;
    const auto bytes = noiseBytes(4, 4, 7);
    const std::string missing = writePngRgb8((dir / "no_folder" / "x.png").string(), 4, 4, bytes.data());
    EXPECT_EQ(missing, std::strerror(ENOENT)) << "the system's reason, not libpng's";
    EXPECT_NE(writePngRgb8((dir / "empty.png").string(), 0, 4, bytes.data()), "");
    EXPECT_FALSE(std::filesystem::exists(dir / "empty.png"));
}

// Whether the OpenImageIO module is mapped into this process.
bool imageCodecLoaded() {
    std::ifstream maps("/proc/self/maps");
    std::string line;
    while (std::getline(maps, line))
        if (line.find("weft_oiio.so") != std::string::npos) return true;
    return false;
}

// In a fresh process (the death test re-runs this test alone): a PNG
// preview leaves the module unloaded, a TIFF preview loads it (the check
// can tell).
TEST(PngWriter, APngPreviewDoesNotLoadOpenImageIo) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    test::TempDir dir;
    Image img(8, 4, {"R", "G", "B", "A"});
    for (float& v : img.data()) v = 0.25f;
    const auto previewLoads = [&](const std::string& name) {
        writePreview(img, (dir / name).string());
        const bool loaded = imageCodecLoaded();
        std::filesystem::remove_all(dir.path());  // exit skips the destructor
        std::exit(loaded ? 1 : 0);
    };
    EXPECT_EXIT(previewLoads("p.png"), ::testing::ExitedWithCode(0), "");
    EXPECT_EXIT(previewLoads("p.tif"), ::testing::ExitedWithCode(1), "");
    writePreview(img, (dir / "p.png").string());
    const Image back = readImage((dir / "p.png").string());
    EXPECT_NEAR(back.at(3, 2, 1), 137 / 255.0f, 1.5 / 255.0) << "sRGB of 0.25 is 137 of 255";
}

}  // namespace
}  // namespace weft
