// weft filter atrous: filters one layer of an EXR guided by its N and P
// layers, keeps the rest, and names missing guide layers in a one-line error
// without writing a file.
#include <gtest/gtest.h>

#include "core/image/io/image_io.hpp"
#include "core/base/rng.hpp"
#include "tests/support/test_support.hpp"

using namespace weft::test;

namespace {

// Noisy RGB on two walls (left faces +x, right faces +z) with N and P layers.
weft::Image noisyWalls(int w, int h) {
    weft::Image img(w, h, {"R", "G", "B", "A", "N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z"});
    weft::Rng rng(3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool left = x < w / 2;
            const float base = left ? 1.0f : 3.0f;
            const float v[10] = {base + rng.uniform() - 0.5f, base + rng.uniform() - 0.5f, base + rng.uniform() - 0.5f, 1,
                                 left ? 1.0f : 0.0f, 0, left ? 0.0f : 1.0f, float(x) * 0.01f, float(y) * 0.01f, 0};
            std::copy(v, v + 10, img.pixel(x, y));
        }
    return img;
}

double sideError(const weft::Image& img, bool left) {
    double err = 0;
    int n = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) {
            if ((x < img.width() / 2) != left) continue;
            const double d = img.at(x, y, 0) - (left ? 1.0 : 3.0);
            err += d * d, ++n;
        }
    return err / n;
}

}  // namespace

TEST(FilterCli, AtrousDenoisesEachWallAndKeepsOtherChannels) {
    TempDir dir;
    const weft::Image in = noisyWalls(48, 32);
    weft::writeExr(in, (dir / "in.exr").string(), {{"weft:technique", "test"}});
    const auto r = runWeft("filter atrous " + (dir / "in.exr").string() + " -o " + (dir / "out.exr").string() +
                           " --set levels=4 --set sigma_normal=0.2 --set sigma_position=1");
    ASSERT_EQ(r.status, 0) << r.output;
    weft::Metadata md;
    const weft::Image out = weft::readImage((dir / "out.exr").string(), &md);
    for (bool left : {true, false}) EXPECT_LT(sideError(out, left), 0.2 * sideError(in, left)) << left;
    EXPECT_EQ(out.at(5, 5, out.channelIndex("N.X")), 1.0f);
    bool levels = false, technique = false;
    for (const auto& [k, v] : md) levels |= k == "weft:filter:atrous:levels" && v == "4", technique |= k == "weft:technique";
    EXPECT_TRUE(levels && technique);
}

TEST(FilterCli, MissingGuideLayersAreNamedAndNoFileIsWritten) {
    TempDir dir;
    weft::Image in(8, 8, {"R", "G", "B", "N.X", "N.Y", "N.Z"});
    weft::writeExr(in, (dir / "in.exr").string(), {});
    const auto r = runWeft("filter atrous " + (dir / "in.exr").string() + " -o " + (dir / "out.exr").string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("P.X, P.Y, P.Z"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.exr"));
    // Without the position term the same file filters.
    const auto ok = runWeft("filter atrous " + (dir / "in.exr").string() + " -o " + (dir / "out.exr").string() +
                            " --set sigma_position=0");
    EXPECT_EQ(ok.status, 0) << ok.output;
    const auto bad = runWeft("filter atrous " + (dir / "in.exr").string() + " -o " + (dir / "o2.exr").string() +
                             " --set levels=99");
    EXPECT_NE(bad.status, 0);
    EXPECT_NE(bad.output.find("levels"), std::string::npos) << bad.output;
}

TEST(FilterCli, SampleCountWeightsReproduceTheAdaptiveTechniquesFilter) {
    // lighting.adaptive_indirect filters indirect_raw with count-weighted taps;
    // the same filter from the command line, weighted by its sampleCount AOV,
    // gives its indirect layer on every surface pixel.
    TempDir dir;
    const std::string img = (dir / "ai.exr").string(), out = (dir / "f.exr").string();
    const std::string filter = " --set levels=3 --set sigma_normal=0.3 --set sigma_position=0.1";
    auto r = runWeft("render " + std::string(WEFT_SOURCE_DIR) + "/scenes/cornell.json --technique lighting.adaptive_indirect"
                     " --res 64x48 --spp 4 --set direct_samples=0 --set min_samples=1 --set min_fraction=0 -o " + img + filter);
    ASSERT_EQ(r.status, 0) << r.output;
    r = runWeft("filter atrous " + img + " -o " + out + " --set layer=indirect_raw --set weights=sampleCount" + filter);
    ASSERT_EQ(r.status, 0) << r.output;
    const weft::Image a = weft::readImage(img, nullptr), f = weft::readImage(out, nullptr);
    int surface = 0, unequalCounts = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            if (a.at(x, y, a.channelIndex("N.X")) == 0 && a.at(x, y, a.channelIndex("N.Y")) == 0 &&
                a.at(x, y, a.channelIndex("N.Z")) == 0)
                continue;  // background
            ++surface, unequalCounts += a.at(x, y, a.channelIndex("sampleCount")) != 4.0f;
            for (const char* c : {"R", "G", "B"})
                ASSERT_NEAR(f.at(x, y, f.channelIndex(std::string("indirect_raw.") + c)),
                            a.at(x, y, a.channelIndex(std::string("indirect.") + c)), 1e-5)
                    << x << "," << y;
        }
    EXPECT_GT(surface, 2000);
    EXPECT_GT(unequalCounts, 300);  // the weights mattered
    r = runWeft("filter atrous " + img + " -o " + (dir / "g.exr").string() + " --set weights=nothing");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("nothing"), std::string::npos) << r.output;
}
