// Every compression round-trips: the lossless ones and b44 (lossy on half
// channels only) bit for bit, pxr24 to 24 bits of float, dwaa/dwab within 10%
// on colour (R, G, B, Y, also as a layer's last part) and exactly on the other channels; half channels keep half precision, saturate at 65504 instead of
// becoming Inf and write NaN as 0; the bytes do not depend on the threads.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <cmath>
#include <limits>

#include "core/base/rng.hpp"
#include "core/image/io/image_io.hpp"
#include "tests/support/test_support.hpp"

namespace weft {
namespace {

// Values a render holds: smooth colour, alpha, normals, and a depth AOV with
// huge, tiny and zero values.
Image renderLike(int w, int h) {
    Image img(w, h, {"R", "G", "B", "A", "N.X", "N.Y", "N.Z", "depth"});
    Rng rng(11);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = img.pixel(x, y);
            for (int c = 0; c < 3; ++c) p[c] = float(0.5 + 0.4 * std::sin(0.1 * x + c) + 0.05 * rng.uniform());
            p[3] = float(rng.uniform());
            p[4] = float(2 * rng.uniform() - 1), p[5] = float(2 * rng.uniform() - 1), p[6] = 0.25f;
            const float depths[] = {1e-30f, 0.0f, 1e30f, 3.5f, float(rng.uniform()) * 1e5f};
            p[7] = depths[(x + y) % 5];
        }
    return img;
}

Image roundTrip(const Image& img, const test::TempDir& dir, const std::string& name, const ExrEncoding& e) {
    const std::string path = (dir / (name + ".exr")).string();
    writeExr(img, path, {}, ImageWindow{0, 0, img.width(), img.height()}, e);
    return readImage(path);
}

TEST(ExrWriter, EveryCompressionRoundTripsFloatChannels) {
    const test::TempDir dir;
    const Image img = renderLike(37, 21);  // not a multiple of any block size
    for (const std::string& c : exrCompressionNames()) {
        SCOPED_TRACE(c);
        const Image back = roundTrip(img, dir, c, {c, {}, 2});
        ASSERT_EQ(back.channelCount(), img.channelCount());
        double worstColour = 0, worstOther = 0;  // relative errors of colour channels and of the rest
        for (int ch = 0; ch < img.channelCount(); ++ch) {
            const std::string& name = img.channelNames()[ch];
            const int b = back.channelIndex(name);  // OpenEXR stores channels sorted by name
            ASSERT_GE(b, 0) << name;
            // DWA's colour rule looks at the part after the last dot: N.Y counts as luminance.
            const std::string last = name.substr(name.rfind('.') + 1);
            double& worst = last == "R" || last == "G" || last == "B" || last == "Y" ? worstColour : worstOther;
            for (int y = 0; y < img.height(); ++y)
                for (int x = 0; x < img.width(); ++x) {
                    const double v = img.at(x, y, ch), r = back.at(x, y, b);
                    worst = std::max(worst, v == 0 ? std::fabs(r) : std::fabs(r - v) / std::fabs(v));
                }
        }
        if (c == "pxr24") {  // 15 of the 23 mantissa bits kept, rounded
            EXPECT_LE(std::max(worstColour, worstOther), std::ldexp(1.0, -15));
        } else if (c == "dwaa" || c == "dwab") {  // a lossy DCT on colour channels, the rest kept
            EXPECT_GT(worstColour, 0.0);
            EXPECT_LE(worstColour, 0.1);
            EXPECT_EQ(worstOther, 0.0);
        } else {  // lossless, or (b44) lossy on half channels only
            EXPECT_EQ(std::max(worstColour, worstOther), 0.0);
        }
    }
}

TEST(ExrWriter, HalfChannelsKeepHalfPrecisionAndStayFinite) {
    const test::TempDir dir;
    Image img = renderLike(16, 10);
    img.at(0, 0, 0) = std::numeric_limits<float>::quiet_NaN();
    img.at(1, 0, 0) = -1e9f;
    const Image back = roundTrip(img, dir, "half", {"zip", {"aovs=half", "R=half"}, 1});
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
            for (int c = 0; c < img.channelCount(); ++c) {
                const float v = img.at(x, y, c), r = back.at(x, y, back.channelIndex(img.channelNames()[c]));
                ASSERT_TRUE(std::isfinite(r)) << x << "," << y << "," << c;
                if (c == 1 || c == 2 || c == 3) {
                    EXPECT_EQ(r, v);  // G, B and A stay float
                } else if (std::isnan(v)) {
                    EXPECT_EQ(r, 0.0f);
                } else if (std::fabs(v) > 65504) {
                    EXPECT_EQ(r, std::copysign(65504.0f, v));
                } else {
                    // Half's 11 significant bits, and its smallest subnormal near zero.
                    EXPECT_LE(std::fabs(r - v), std::fabs(v) * std::ldexp(1.0, -11) + std::ldexp(1.0, -24)) << c;
                }
            }
    Imf::InputFile file((dir / "half.exr").string().c_str());
    const Imf::ChannelList& channels = file.header().channels();
    EXPECT_EQ(channels.findChannel("R")->type, Imf::HALF);
    EXPECT_EQ(channels.findChannel("G")->type, Imf::FLOAT);
    EXPECT_EQ(channels.findChannel("A")->type, Imf::FLOAT);
    EXPECT_EQ(channels.findChannel("N.Y")->type, Imf::HALF);
    EXPECT_EQ(channels.findChannel("depth")->type, Imf::HALF);
}

TEST(ExrWriter, SameBytesOnAnyThreadCount) {
    const test::TempDir dir;
    const Image img = renderLike(64, 200);
    for (const char* c : {"zip", "piz", "dwaa"}) {
        SCOPED_TRACE(c);
        std::string bytes[2];
        for (int t : {1, 3}) {
            const std::string path = (dir / ("t" + std::to_string(t) + ".exr")).string();
            writeExr(img, path, {{"weft:x", "1"}}, ImageWindow{0, 0, 64, 200}, {c, {"aovs=half"}, t});
            bytes[t == 3] = test::readBytes(path);
        }
        EXPECT_EQ(bytes[0], bytes[1]);
    }
}

}  // namespace
}  // namespace weft
