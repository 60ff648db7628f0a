// EXRs read through OpenEXR give what OpenImageIO gives for the same file:
// channels in the same order, the same float pixels, windows and string
// attributes, for scanline and tiled files of float and half channels with a
// data window inside the display window; uint channels read as their values; what the direct reader
// leaves (subsampled channels) still reads through OpenImageIO; a file cut
// short is refused with one line.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledOutputFile.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/image/io/exr_reader.hpp"
#include "core/image/io/image_codec.hpp"
#include "core/image/io/image_io.hpp"
#include "tests/support/test_support.hpp"

namespace weft {
namespace {

// Names OpenImageIO orders specially, layers, and plain names, in no order.
const std::vector<std::string> kNames = {"zeta", "depth", "A", "B", "G", "R", "albedo.B", "albedo.R", "Y",
                                         "N.X", "N.Z", "x.y.R", "x.B", "Z", "alpha", "g", "RA", "imag", ".R"};

struct Written {
    std::string path;
    int w, h;
};

// A file of kNames with pixel types cycling float, half (and uint); data
// window (3, 5)-(3+w-1, 5+h-1) inside a larger display window; scanlines or tiles.
Written writeTestFile(const test::TempDir& dir, const std::string& name, bool tiled, bool withUint = false) {
    const int w = 29, h = 13, x0 = 3, y0 = 5;
    Imf::Header header(Imath::Box2i({0, 0}, {40, 30}), Imath::Box2i({x0, y0}, {x0 + w - 1, y0 + h - 1}));
    header.insert("weft:note", Imf::StringAttribute("a string"));
    header.insert("studio:shot", Imf::StringAttribute("sq010"));
    if (tiled) header.setTileDescription(Imf::TileDescription(8, 8, Imf::ONE_LEVEL));
    const Imf::PixelType types[] = {Imf::FLOAT, Imf::HALF, Imf::UINT};
    std::vector<std::vector<float>> floats(kNames.size());
    std::vector<std::vector<Imath::half>> halves(kNames.size());
    std::vector<std::vector<std::uint32_t>> uints(kNames.size());
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < kNames.size(); ++c) {
        const Imf::PixelType t = types[c % (withUint ? 3 : 2)];
        header.channels().insert(kNames[c], Imf::Channel(t));
        floats[c].resize(std::size_t(w) * h), halves[c].resize(floats[c].size()), uints[c].resize(floats[c].size());
        for (int i = 0; i < w * h; ++i) {
            floats[c][i] = float(c) * 100.0f + float(i) * 0.37f - 50.0f;
            halves[c][i] = Imath::half(floats[c][i]);
            uints[c][i] = std::uint32_t(c * 1000 + i);
        }
        char* base = t == Imf::FLOAT ? reinterpret_cast<char*>(floats[c].data())
                     : t == Imf::HALF ? reinterpret_cast<char*>(halves[c].data())
                                      : reinterpret_cast<char*>(uints[c].data());
        const std::size_t bytes = t == Imf::HALF ? 2 : 4;
        frame.insert(kNames[c], Imf::Slice(t, base - (x0 + std::ptrdiff_t(y0) * w) * bytes, bytes, bytes * w));
    }
    const std::string path = (dir / (name + ".exr")).string();
    if (tiled) {
        Imf::TiledOutputFile out(path.c_str(), header);
        out.setFrameBuffer(frame);
        out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
    } else {
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(h);
    }
    return {path, w, h};
}

std::vector<std::pair<std::string, std::string>> withoutSynthesized(std::vector<std::pair<std::string, std::string>> a) {
    // OpenImageIO adds a colour space the file does not name.
    std::erase_if(a, [](const auto& kv) { return kv.first == "oiio:ColorSpace"; });
    std::sort(a.begin(), a.end());
    return a;
}

void expectSameAsCodec(const std::string& path) {
    ImageFileSpec direct, codec;
    std::vector<float> directPixels, codecPixels;
    ASSERT_EQ(readExrFile(path, direct, directPixels), ExrRead::Read);
    ASSERT_EQ(imageCodec().read(path, codec, codecPixels), "");
    EXPECT_EQ(direct.channels, codec.channels);
    EXPECT_EQ(direct.width, codec.width);
    EXPECT_EQ(direct.height, codec.height);
    EXPECT_EQ(direct.x, codec.x);
    EXPECT_EQ(direct.y, codec.y);
    EXPECT_EQ(direct.fullWidth, codec.fullWidth);
    EXPECT_EQ(direct.fullHeight, codec.fullHeight);
    EXPECT_EQ(withoutSynthesized(direct.attributes), withoutSynthesized(codec.attributes));
    ASSERT_EQ(directPixels.size(), codecPixels.size());
    for (std::size_t i = 0; i < directPixels.size(); ++i) ASSERT_EQ(directPixels[i], codecPixels[i]) << "value " << i;
}

TEST(ExrReader, ScanlineFileReadsAsOpenImageIoReadsIt) {
    const test::TempDir dir;
    expectSameAsCodec(writeTestFile(dir, "scan", false).path);
}

TEST(ExrReader, TiledFileReadsAsOpenImageIoReadsIt) {
    const test::TempDir dir;
    expectSameAsCodec(writeTestFile(dir, "tiles", true).path);
}

TEST(ExrReader, UintChannelsReadAsTheirValues) {
    const test::TempDir dir;
    const Written f = writeTestFile(dir, "uint", false, true);
    Metadata md;
    const Image img = readImage(f.path, &md);
    for (std::size_t c = 2; c < kNames.size(); c += 3) {  // the uint channels
        const int ch = img.channelIndex(kNames[c]);
        ASSERT_GE(ch, 0) << kNames[c];
        EXPECT_EQ(img.at(0, 0, ch), float(c * 1000)) << kNames[c];
        EXPECT_EQ(img.at(f.w - 1, f.h - 1, ch), float(c * 1000 + f.w * f.h - 1)) << kNames[c];
    }
}

TEST(ExrReader, WhatWeftWritesReadsBackWithItsMetadata) {
    const test::TempDir dir;
    Image img(5, 3, {"R", "G", "B", "A", "depth"});
    for (std::size_t i = 0; i < img.data().size(); ++i) img.data()[i] = float(i) * 0.25f;
    const std::string path = (dir / "w.exr").string();
    writeExr(img, path, {{"weft:technique", "volume.raymarch"}}, ImageWindow{2, 1, 9, 8});
    Metadata md;
    ImageWindow window;
    const Image back = readImage(path, &md, &window);
    EXPECT_EQ(back.channelNames(), img.channelNames());
    EXPECT_EQ(back.data(), img.data());
    EXPECT_EQ(window.x, 2);
    EXPECT_EQ(window.y, 1);
    EXPECT_EQ(window.fullWidth, 9);
    EXPECT_EQ(window.fullHeight, 8);
    EXPECT_NE(std::find(md.begin(), md.end(), std::pair<std::string, std::string>{"weft:technique", "volume.raymarch"}), md.end());
}

TEST(ExrReader, ChannelOrderPutsLayersThenColourFirst) {
    const std::vector<std::string> names = {".R", "A", "B", "G", "N.X", "R", "Z", "alpha", "b", "x.B", "zeta"};
    std::vector<std::string> ordered;
    for (int i : exrChannelOrder(names)) ordered.push_back(names[i]);
    EXPECT_EQ(ordered, (std::vector<std::string>{"R", "G", "B", "b", "A", "alpha", "Z", "zeta", ".R", "N.X", "x.B"}));
    // A layer of X and Y or Z is a vector: X, Y, Z before alpha; elsewhere Y ranks before A and Z after it.
    const std::vector<std::string> vectors = {"N.Z", "N.A", "N.X", "N.Y", "c.Z", "c.A", "c.Y", "P.x", "P.z"};
    ordered.clear();
    for (int i : exrChannelOrder(vectors)) ordered.push_back(vectors[i]);
    EXPECT_EQ(ordered, (std::vector<std::string>{"N.X", "N.Y", "N.Z", "N.A", "P.x", "P.z", "c.Y", "c.A", "c.Z"}));
}

TEST(ExrReader, SubsampledChannelsAreLeftToOpenImageIo) {
    const test::TempDir dir;
    const int w = 8, h = 4;
    Imf::Header header(w, h);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    header.channels().insert("RY", Imf::Channel(Imf::FLOAT, 2, 2));
    std::vector<float> y(w * h, 0.5f), ry(w * h / 4, 0.25f);
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data()), 4, 4 * w));
    frame.insert("RY", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(ry.data()), 4, 4 * w / 2, 2, 2));
    const std::string path = (dir / "sub.exr").string();
    {
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(h);
    }
    ImageFileSpec spec;
    std::vector<float> pixels;
    EXPECT_EQ(readExrFile(path, spec, pixels), ExrRead::NeedsCodec);
    ImageFileSpec codec;
    std::vector<float> codecPixels;
    const std::string codecError = imageCodec().read(path, codec, codecPixels);
    // readImage gives what OpenImageIO gives: the same pixels, or its refusal.
    if (codecError.empty()) {
        const Image back = readImage(path);
        EXPECT_EQ(std::vector<float>(back.data().begin(), back.data().end()), codecPixels);
    }
    else
        EXPECT_NE(test::errorOf([&] { readImage(path); }).find(codecError), std::string::npos);
}

TEST(ExrReader, PixelsCutShortAreRefusedInOneLine) {
    const test::TempDir dir;
    const Written good = writeTestFile(dir, "good", false);
    std::ifstream in(good.path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    // Keep the header and offset table, overwrite the last chunks with garbage.
    for (std::size_t i = bytes.size() * 3 / 4; i < bytes.size(); ++i) bytes[i] = char(0xA5 ^ i);
    const std::string bad = (dir / "bad.exr").string();
    std::ofstream(bad, std::ios::binary) << bytes;
    const std::string error = test::errorOf([&] { readImage(bad); });
    EXPECT_NE(error.find("image '" + bad + "': cannot be read"), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

}  // namespace
}  // namespace weft
