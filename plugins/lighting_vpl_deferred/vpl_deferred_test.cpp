// lighting.vpl_deferred: agreement with the path tracer's one-bounce result,
// clamp compensation that keeps the mean, interleaving that shades each
// pixel with exactly its subset, and images independent of thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/base/error.hpp"
#include "tests/support/mesh_fixtures.hpp"
#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;

namespace {

const std::string kCornell = std::string(WEFT_SOURCE_DIR) + "/scenes/cornell.json";

RenderOutcome vpl(const std::string& res, std::vector<std::string> sets, std::uint64_t seed = 0, int threads = 0) {
    RenderRequest r;
    r.input = kCornell, r.resolution = parseResolution(res), r.technique = "lighting.vpl_deferred", r.sets = std::move(sets);
    r.seed = seed, r.threads = threads;
    return renderToImage(r);
}

// Relative RMS difference of the RGB channels, leaving out the `trim` pixels
// that differ most: at a corner a pixel-centre ray may land on either face,
// and Embree's single-ray and stream traversals need not pick the same one.
double relativeRms(const Image& a, const Image& b, std::size_t trim = 3) {
    std::vector<std::pair<double, double>> px;  // squared error, squared reference
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            double se = 0, ref = 0;
            for (int c = 0; c < 3; ++c) {
                const double d = a.at(x, y, c) - b.at(x, y, c);
                se += d * d, ref += double(b.at(x, y, c)) * b.at(x, y, c);
            }
            px.emplace_back(se, ref);
        }
    std::sort(px.begin(), px.end());
    double se = 0, ref = 0;
    for (std::size_t i = 0; i + trim < px.size(); ++i) se += px[i].first, ref += px[i].second;
    return std::sqrt(se / ref);
}

struct MeanAndError {
    double mean, stderr_;
};

// Mean over seeds of the image mean of one channel, with its standard error.
MeanAndError meanOverSeeds(const std::vector<std::string>& sets, const std::string& channel, int seeds) {
    double s = 0, s2 = 0;
    for (int k = 0; k < seeds; ++k) {
        const Image img = vpl("16x16", sets, std::uint64_t(100 + k)).image;
        const double m = test::channelMean(img, img.channelIndex(channel));
        s += m, s2 += m * m;
    }
    const double mean = s / seeds;
    return {mean, std::sqrt(std::max(0.0, s2 / seeds - mean * mean) / (seeds - 1))};
}

}  // namespace

TEST(VplDeferred, ConvergesToThePathTracersOneBounce) {
    // Two independent path-traced references: their difference measures the
    // references' own noise, the floor any converged estimate sits on.
    RenderRequest r;
    r.input = kCornell, r.resolution = Resolution{24, 24}, r.technique = "mesh.pathtrace";
    r.sets = {"max_depth=2", "jitter=false"}, r.spp = 2048, r.seed = 7;
    const Image reference = renderToImage(r).image;
    r.seed = 8;
    const double floor = relativeRms(renderToImage(r).image, reference) / std::sqrt(2.0);
    double err[3];
    int k = 0;
    Image last;
    for (const char* paths : {"32", "256", "2048"}) {
        last = vpl("24x24", {"interleave=1x1", std::string("vpls=") + paths, "bias_compensation=8"}).image;
        err[k++] = relativeRms(last, reference);
    }
    std::printf("relative RMS vs path tracer: %.4f %.4f %.4f (reference noise %.4f)\n", err[0], err[1], err[2], floor);
    EXPECT_LT(err[1], 0.75 * err[0]);
    EXPECT_LT(err[2], 0.75 * err[1]);
    EXPECT_LT(err[2], 0.005);
    EXPECT_LT(floor, 0.5 * err[2]);  // the references are precise enough to see the trend
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(test::channelMean(last, c), test::channelMean(reference, c), 0.01 * test::channelMean(reference, c));
    EXPECT_GT(test::channelMean(last, 0), 0.1);
}

TEST(VplDeferred, PointAndDirectionalLightsAgreeWithThePathTracer) {
    // A subdivided torus lit by a directional and a point light: direct light
    // is exact per pixel, bounce VPLs start from both lights.
    test::TempDir dir;
    test::writeText(dir / "torus.json", R"({"meshes": [{"file": ")" + std::string(WEFT_SOURCE_DIR) +
                                            R"(/data/catmark_torus_creases0.obj", "subdivision": 2}],
        "lights": [{"type": "directional", "direction": [0.3, -0.6, -1], "intensity": 2},
                   {"type": "point", "position": [0, 2, 2], "intensity": 3}],
        "camera": {"eye": [0, 2.5, 3], "target": [0, 0, 0], "fov": 40}})");
    RenderRequest r;
    r.input = (dir / "torus.json").string(), r.resolution = Resolution{24, 24}, r.technique = "mesh.pathtrace";
    r.sets = {"max_depth=2", "jitter=false"}, r.spp = 512, r.seed = 3;
    const Image reference = renderToImage(r).image;
    r.technique = "lighting.vpl_deferred", r.sets = {"interleave=1x1", "vpls=2048"}, r.spp.reset();
    const Image img = renderToImage(r).image;
    EXPECT_LT(relativeRms(img, reference), 0.02);
    const double indirect = test::channelMean(img, img.channelIndex("indirect.G"));
    EXPECT_GT(indirect, 1e-4);  // the bounce VPLs do light it
    EXPECT_NEAR(test::channelMean(img, 1), test::channelMean(reference, 1), 0.01 * test::channelMean(reference, 1));
}

TEST(VplDeferred, ClampCompensationKeepsTheMean) {
    const int seeds = 12;
    const std::vector<std::string> base = {"interleave=1x1", "vpls=128"};
    auto with = [&](std::vector<std::string> extra) {
        extra.insert(extra.end(), base.begin(), base.end());
        return meanOverSeeds(extra, "indirect.G", seeds);
    };
    const MeanAndError unclamped = with({"clamp=0"});
    const MeanAndError compensated = with({"clamp=0.3", "bias_compensation=4"});
    const MeanAndError lossy = with({"clamp=0.3", "bias_compensation=0"});
    const double noise = std::hypot(unclamped.stderr_, compensated.stderr_);
    std::printf("unclamped %.5f +- %.5f, compensated %.5f +- %.5f, clamped only %.5f +- %.5f\n", unclamped.mean,
                unclamped.stderr_, compensated.mean, compensated.stderr_, lossy.mean, lossy.stderr_);
    EXPECT_LT(std::abs(compensated.mean - unclamped.mean), 3 * noise);
    // The clamp alone does lose energy, so the comparison above has power.
    EXPECT_GT(unclamped.mean - lossy.mean, 3 * std::hypot(unclamped.stderr_, lossy.stderr_));
}

TEST(VplDeferred, SameImageAtOneAndTwoThreads) {
    const std::vector<std::string> sets = {"interleave=4x3", "vpls=60", "kernel=5"};
    const Image a = vpl("37x29", sets, 3, 1).image, b = vpl("37x29", sets, 3, 2).image;
    EXPECT_EQ(a.data(), b.data());
}

// Shading through the interleave (fused) and shading split copies (one or
// two passes, gathered back) light every texel with the same VPLs in the
// same order: the same image to the bit, sizes the pattern does not divide included.
TEST(VplDeferred, FusedAndCopiedSplitsGiveTheSameImage) {
    const Image fused = vpl("37x29", {"interleave=4x3"}).image;
    const Image a = vpl("37x29", {"interleave=4x3", "split=one_pass"}).image;
    const Image b = vpl("37x29", {"interleave=4x3", "split=two_pass", "block=8x9"}).image;
    EXPECT_EQ(a.data(), b.data());
    EXPECT_EQ(fused.data(), a.data());
    EXPECT_GT(test::channelMean(fused, fused.channelIndex("indirect.R")), 0);
}

TEST(VplDeferred, EachPixelIsShadedByExactlyItsSubset) {
    // 1x1 is plain deferred shading: every VPL at every covered pixel. With an
    // n x m pattern each pixel sees only the VPLs of its sub-buffer's paths.
    const RenderOutcome plain = vpl("32x32", {"interleave=1x1", "vpls=96"});
    const RenderOutcome inter = vpl("32x32", {"interleave=4x2", "vpls=96"});
    const std::int64_t covered = plain.counters.at("fragments.gbuffer");  // the box fills the frame
    const std::int64_t vpls = plain.counters.at("vpl.emitter") + plain.counters.at("vpl.bounce");
    EXPECT_EQ(plain.counters.at("fragments.shaded"), covered * vpls);
    EXPECT_NEAR(double(inter.counters.at("fragments.shaded")), double(covered * vpls) / 8, double(covered * vpls) * 0.05 / 8);
    EXPECT_LT(inter.counters.at("rays.shadow"), plain.counters.at("rays.shadow") / 6);
}

TEST(VplDeferred, AovsAreConsistent) {
    const Image img = vpl("20x16", {"interleave=3x2", "vpls=48"}).image;
    const int direct = img.channelIndex("direct.R"), indirect = img.channelIndex("indirect.R");
    const int albedo = img.channelIndex("albedo.R"), sub = img.channelIndex("subbuffer"), z = img.channelIndex("Z");
    for (int c : {direct, indirect, albedo, sub, z, img.channelIndex("N.X"), img.channelIndex("discontinuity")}) ASSERT_GE(c, 0);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 20; ++x) {
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(img.at(x, y, c), img.at(x, y, direct + c) + img.at(x, y, indirect + c), 1e-5f);
            EXPECT_EQ(img.at(x, y, sub), float((y % 2) * 3 + x % 3));
            if (img.at(x, y, z) == 0.0f) {  // background
                EXPECT_EQ(img.at(x, y, albedo), 0.0f);
            }
        }
}

TEST(VplDeferred, IgnoringVisibilityOnlyAddsLight) {
    const Image ssm = vpl("24x24", {"interleave=2x2", "bias_compensation=0", "filter=false"}).image;
    const Image snsm = vpl("24x24", {"interleave=2x2", "bias_compensation=0", "filter=false", "visibility=false"}).image;
    double more = 0;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x)
            for (int c = 0; c < 3; ++c) {
                EXPECT_GE(snsm.at(x, y, c), ssm.at(x, y, c) - 1e-6f);
                more += snsm.at(x, y, c) - ssm.at(x, y, c);
            }
    EXPECT_GT(more, 1.0);  // the boxes do cast shadows
}

TEST(VplDeferred, BadParametersAreClearErrors) {
    auto message = [](std::vector<std::string> sets) {
        try {
            vpl("8x8", std::move(sets));
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(message({"interleave=4x4", "split=two_pass", "block=6x8"}).find("block=6x8 must be a multiple of interleave=4x4"), std::string::npos);
    EXPECT_NE(message({"interleave=4"}).find("interleave"), std::string::npos);
    EXPECT_NE(message({"interleave=8x6", "vpls=20"}).find("without VPLs"), std::string::npos);
}

TEST(VplDeferred, ExtremeSettingsStayFinite) {
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {"1x1", {"interleave=1x1", "vpls=1", "clamp=0"}},                    // one path, unclamped singularities
        {"3x2", {"interleave=64x64", "vpls=4096", "kernel=63"}},            // pattern far larger than the image
        {"17x9", {"interleave=5x3", "vpls=15", "clamp=10", "bias_compensation=2"}},  // clamp everything, compensate it all
        {"16x16", {"interleave=2x2", "normal_threshold=0", "position_threshold=0"}},  // every pixel a discontinuity
    };
    for (const auto& [res, sets] : cases) {
        const RenderOutcome out = vpl(res, sets);
        EXPECT_EQ(out.counters.count("image.nonfinite"), 0u) << res;  // the host would have scrubbed them
        double sum = 0;
        for (float v : out.image.data()) sum += v;
        EXPECT_GT(sum, 0.0) << res;
    }
}

namespace {

// A glossy floor, a diffuse back wall and a small light above, built in code.
Scene glossyStage() {
    auto quad = [](Vec3f a, Vec3f b, Vec3f c, Vec3f d, const Material& m) {
        TriangleMesh q;
        q.positions = {a, b, c, d};
        q.indices = {0, 1, 2, 0, 2, 3};
        q.material = {0, 0};
        q.materials = {m};
        return q;
    };
    Material floor, wall, light;
    floor.diffuse = Vec3f(0.3f, 0.3f, 0.3f), floor.glossy = Vec3f(0.5f, 0.5f, 0.5f), floor.exponent = 30;
    wall.diffuse = Vec3f(0.7f, 0.6f, 0.5f);
    light.diffuse = Vec3f(0, 0, 0), light.emission = Vec3f(8, 8, 8);
    Scene scene;
    scene.source = "glossy stage";
    scene.addMesh(quad({-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, floor));           // faces +y
    scene.addMesh(quad({-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}, wall));          // faces +z
    scene.addMesh(quad({-0.2f, 1.2f, -0.4f}, {0.2f, 1.2f, -0.4f}, {0.2f, 1.2f, 0.0f}, {-0.2f, 1.2f, 0.0f}, light));  // faces -y
    scene.camera.eye = Vec3d(0, 0.9, 2.6), scene.camera.target = Vec3d(0, 0.4, 0);
    return scene;
}

}  // namespace

TEST(VplDeferred, GlossyLobesAgreeWithThePathTracer) {
    const Scene scene = glossyStage();
    for (const char* model : {"phong", "blinn"}) {
        const Image reference = test::renderScene(scene, "mesh.pathtrace", {{"max_depth", "2"}, {"jitter", "false"}, {"glossy", model}}, 24, 24, 1024, 5);
        const Image img = test::renderScene(scene, "lighting.vpl_deferred",
                                            {{"interleave", "1x1"}, {"vpls", "2048"}, {"glossy", model}, {"bias_compensation", "4"}}, 24, 24, 1);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(test::channelMean(img, c), test::channelMean(reference, c), 0.015 * test::channelMean(reference, c)) << model;
        const double err = relativeRms(img, reference);
        std::printf("%s: relative RMS %.4f\n", model, err);
        EXPECT_LT(err, 0.1) << model;  // glossy highlights keep both estimates noisy per pixel
    }
}
