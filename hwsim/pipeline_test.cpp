// Per-stage tests of the modelled pipeline on small hand-counted cases.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/error.hpp"
#include "hwsim/pipeline.hpp"

namespace weft::hwsim {
namespace {

struct Flat {  // writes white, never discards
    void operator()(const Fragment&, FragmentOutput& o) const { o.color = {1, 1, 1, 1}; }
};

Profile withRule(FillRule rule) {
    Profile p = findProfile("ideal");
    p.fillRule = rule;
    return p;
}

std::int64_t coveredBy(const Vertex (&v)[3], FillRule rule) {
    Framebuffer fb(8, 8);
    const Profile profile = withRule(rule);
    Pipeline pipe(fb, profile);
    pipe.drawTriangle(v, Flat{});
    return pipe.counts().generated;
}

// Legs on x = 0.5 and y = 0.5, hypotenuse x + y = 5: 3 centres strictly
// inside, 5 on each leg and 5 on the hypotenuse (3 corners shared).
TEST(HwsimRaster, CentresOnEdgesFollowTheFillRule) {
    const Vertex tri[3] = {{0.5f, 0.5f, 0}, {4.5f, 0.5f, 0}, {0.5f, 4.5f, 0}};
    EXPECT_EQ(coveredBy(tri, FillRule::TopLeft), 6);      // left leg without its ends + 3
    EXPECT_EQ(coveredBy(tri, FillRule::BottomLeft), 10);  // both legs + 3
    EXPECT_EQ(coveredBy(tri, FillRule::BottomRight), 10); // bottom leg without (0,0), hypotenuse + 3
    EXPECT_EQ(coveredBy(tri, FillRule::TopRight), 6);     // hypotenuse without its ends + 3
    const Vertex cw[3] = {tri[0], tri[2], tri[1]};        // winding does not matter
    EXPECT_EQ(coveredBy(cw, FillRule::TopLeft), 6);
}

// Softpipe's float spans on the same triangle: bottom leg and hypotenuse
// (a right edge) in, the left leg out — as Mesa's softpipe draws it.
TEST(HwsimRaster, FloatSpansMatchSoftpipesRule) {
    const Vertex tri[3] = {{0.5f, 0.5f, 0}, {4.5f, 0.5f, 0}, {0.5f, 4.5f, 0}};
    SpanRows rows;
    const PrimitiveSetup s = setupTriangleSpans(tri, 8, 8, rows);
    int covered = 0;
    for (int y = s.y0; y < s.y1; ++y)
        for (int x = s.x0; x < s.x1; ++x) covered += s.covers(x, y);
    EXPECT_EQ(covered, 10);
    EXPECT_FALSE(s.covers(0, 1));
    EXPECT_TRUE(s.covers(4, 0));
    EXPECT_TRUE(s.covers(1, 3));
    EXPECT_FALSE(s.covers(1, 4));
}

TEST(HwsimRaster, SharedEdgesCoverEveryPixelOnce) {
    // A 6x4 quad whose diagonal passes through pixel centres.
    const Vertex q[4] = {{1, 1, 0}, {7, 1, 0}, {7, 5, 0}, {1, 5, 0}};
    for (FillRule rule : {FillRule::TopLeft, FillRule::TopRight, FillRule::BottomLeft, FillRule::BottomRight}) {
        Framebuffer fb(8, 8);
        const Profile profile = withRule(rule);
        Pipeline pipe(fb, profile);
        pipe.state.blend = {true, BlendFactor::One, BlendFactor::One};
        pipe.drawQuad(q, Flat{});
        EXPECT_EQ(pipe.counts().generated, 24);
        for (std::size_t i = 0; i < fb.color.size(); i += 4) EXPECT_TRUE(fb.color[i] == 0 || fb.color[i] == 1);  // never twice
    }
}

TEST(HwsimRaster, DegenerateAndOffscreenCoverNothing) {
    Framebuffer fb(8, 8);
    Pipeline pipe(fb, findProfile("ideal"));
    const Vertex line[3] = {{0, 0, 0}, {4, 4, 0}, {8, 8, 0}};
    const Vertex off[3] = {{-10, -10, 0}, {-2, -10, 0}, {-2, -2, 0}};
    pipe.drawTriangle(line, Flat{});
    pipe.drawTriangle(off, Flat{});
    EXPECT_EQ(pipe.counts().generated, 0);
}

TEST(HwsimRaster, ExtremesAreEmptyOrClearErrors) {
    Framebuffer fb(8, 8);
    Pipeline pipe(fb, findProfile("ideal"));
    const float nan = std::nanf(""), inf = INFINITY;
    const Vertex bad[3] = {{0, 0, nan}, {8, 0, 0}, {0, 8, 0}}, worse[3] = {{inf, 0, 0}, {8, 0, 0}, {0, 8, 0}};
    pipe.drawTriangle(bad, Flat{});
    pipe.drawTriangle(worse, Flat{});
    EXPECT_EQ(pipe.counts().generated, 0);
    const Vertex huge[3] = {{-3e6f, 0, 0}, {8, 0, 0}, {0, 8, 0}};
    EXPECT_THROW(pipe.drawTriangle(huge, Flat{}), Error);
    const Vertex big[3] = {{-1e6f, -1e6f, 0.5f}, {1e6f, -1e6f, 0.5f}, {0, 1e6f, 0.5f}};  // covers the target
    pipe.state.depth = {true, CompareFunc::Always, true};
    pipe.drawTriangle(big, [](const Fragment&, FragmentOutput& o) { o.depth = std::nanf(""); }, {.writesDepth = true});
    EXPECT_EQ(pipe.counts().generated, 64);
    for (float d : fb.depth) EXPECT_EQ(d, 0.0f);  // a NaN program depth is stored as 0, never as NaN
}

TEST(HwsimStipple, KeepsOneClassAndRepeatsEvery32Pixels) {
    Framebuffer fb(64, 64);
    Pipeline pipe(fb, findProfile("ideal"));
    pipe.state.stipple = {true, StippleState::interleaved(4, 1, 2)};
    pipe.drawRect(0, 0, 64, 64, 0, Flat{});
    EXPECT_EQ(pipe.counts().generated, 4096);
    EXPECT_EQ(pipe.counts().rejected[int(Stage::Stipple)], 4096 - 256);
    EXPECT_EQ(pipe.counts().invocations, 256);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const bool kept = fb.colorAt(fb.index(x, y))[0] == 1;
            EXPECT_EQ(kept, x % 4 == 1 && y % 4 == 2);
            EXPECT_EQ(kept, fb.colorAt(fb.index(x + 32, y + 32))[0] == 1);
        }
}

TEST(HwsimStipple, LateStippleRunsTheProgramFirst) {
    Framebuffer fb(64, 64);
    Pipeline pipe(fb, findProfile("geforce-7800"));
    pipe.state.stipple = {true, StippleState::interleaved(2, 0, 0)};
    pipe.drawRect(0, 0, 64, 64, 0, Flat{});
    EXPECT_EQ(pipe.counts().invocations, 4096);
    EXPECT_EQ(pipe.counts().rejected[int(Stage::Stipple)], 3072);
    EXPECT_EQ(pipe.counts().samplesPassed, 1024);
}

// A kill at the program's start: the program runs for every covered pixel,
// the stippled ones as dropped (helper) runs, and the early depth test is
// lost to it when depth is written (modern-desktop's discard rule).
TEST(HwsimStipple, KillAtProgramStartRunsButDropsTheFragment) {
    Framebuffer fb(64, 64);
    Pipeline pipe(fb, findProfile("modern-desktop"));
    pipe.state.stipple = {true, StippleState::interleaved(2, 0, 0)};
    pipe.drawRect(0, 0, 64, 64, 0, Flat{});
    EXPECT_EQ(pipe.counts().invocations, 4096);
    EXPECT_EQ(pipe.counts().helpers, 3072);
    EXPECT_EQ(pipe.counts().rejected[int(Stage::Stipple)], 3072);
    EXPECT_EQ(pipe.counts().samplesPassed, 1024);
    pipe.state.depth = {true, CompareFunc::Less, true};
    EXPECT_FALSE(pipe.plan({}).zsEarly);
    pipe.state.depth.writeMask = false;
    EXPECT_TRUE(pipe.plan({}).zsEarly);
}

TEST(HwsimScissor, KeepsTheRectangle) {
    Framebuffer fb(16, 16);
    Pipeline pipe(fb, findProfile("ideal"));
    pipe.state.scissor = {true, 2, 3, 4, 5};
    pipe.drawRect(0, 0, 10, 10, 0, Flat{});
    EXPECT_EQ(pipe.counts().generated, 100);
    EXPECT_EQ(pipe.counts().rejected[int(Stage::Scissor)], 80);
    EXPECT_EQ(pipe.counts().pixelsWritten, 20);
    EXPECT_EQ(fb.colorAt(fb.index(2, 3))[0], 1);
    EXPECT_EQ(fb.colorAt(fb.index(6, 3))[0], 0);
    EXPECT_EQ(fb.colorAt(fb.index(5, 8))[0], 0);
}

// Stored depths 0.25, 0.5, 0.75, 1 in columns; the fragment's own depth (0.9) plays no part.
TEST(HwsimBounds, TestsStoredDepthWithInclusiveEdges) {
    for (const char* name : {"ideal", "mesa-softpipe", "geforce-7800", "modern-desktop"}) {
        Framebuffer fb(4, 2);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 4; ++x) fb.depth[fb.index(x, y)] = 0.25f * float(x + 1);
        Pipeline pipe(fb, findProfile(name));
        pipe.state.bounds = {true, 0.25f, 0.5f};
        pipe.drawRect(0, 0, 4, 2, 0.9f, Flat{});
        EXPECT_EQ(pipe.counts().samplesPassed, 4) << name;
        EXPECT_EQ(pipe.counts().rejected[int(Stage::Bounds)], 4) << name;
        EXPECT_EQ(fb.colorAt(fb.index(1, 1))[0], 1) << name;
        EXPECT_EQ(fb.colorAt(fb.index(2, 1))[0], 0) << name;
    }
}

TEST(HwsimBounds, UnsupportedFeatureIsAClearError) {
    Framebuffer fb(4, 4);
    Pipeline pipe(fb, findProfile("mesa-llvmpipe"));
    pipe.state.bounds = {true, 0, 0.5f};
    try {
        pipe.drawRect(0, 0, 4, 4, 0, Flat{});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("depth bounds"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("mesa-llvmpipe"), std::string::npos);
    }
}

std::uint8_t stencilAfter(StencilOp op, std::uint8_t start, std::uint8_t writeMask = 0xff) {
    Framebuffer fb(2, 2);
    fb.stencil.assign(4, start);
    Pipeline pipe(fb, findProfile("ideal"));
    pipe.state.stencil.enabled = true;
    pipe.state.stencil.dppass = op;
    pipe.state.stencil.ref = 0x5a;
    pipe.state.stencil.writeMask = writeMask;
    pipe.drawRect(0, 0, 2, 2, 0, Flat{});
    return fb.stencil[0];
}

TEST(HwsimStencil, OpsWrapOrSaturate) {
    EXPECT_EQ(stencilAfter(StencilOp::Incr, 255), 255);
    EXPECT_EQ(stencilAfter(StencilOp::IncrWrap, 255), 0);
    EXPECT_EQ(stencilAfter(StencilOp::Decr, 0), 0);
    EXPECT_EQ(stencilAfter(StencilOp::DecrWrap, 0), 255);
    EXPECT_EQ(stencilAfter(StencilOp::Incr, 7), 8);
    EXPECT_EQ(stencilAfter(StencilOp::Invert, 0x0f), 0xf0);
    EXPECT_EQ(stencilAfter(StencilOp::Replace, 0), 0x5a);
    EXPECT_EQ(stencilAfter(StencilOp::Zero, 9), 0);
    EXPECT_EQ(stencilAfter(StencilOp::Replace, 0xff, 0x0f), 0xfa);  // only the low bits change
    EXPECT_EQ(stencilAfter(StencilOp::Keep, 3), 3);
}

TEST(HwsimStencil, FuncComparesMaskedReferenceAndAppliesFailOps) {
    Framebuffer fb(4, 1);
    fb.stencil = {0x01, 0x11, 0x02, 0x12};
    Pipeline pipe(fb, findProfile("ideal"));
    StencilState& s = pipe.state.stencil;
    s = {true, CompareFunc::Equal, 0x31, 0x0f, 0xff, StencilOp::IncrWrap, StencilOp::Keep, StencilOp::Zero};
    pipe.drawRect(0, 0, 4, 1, 0, Flat{});
    EXPECT_EQ(pipe.counts().rejected[int(Stage::Stencil)], 2);
    EXPECT_EQ(pipe.counts().samplesPassed, 2);
    EXPECT_EQ(fb.stencil, (LargeBuffer<std::uint8_t>{0x00, 0x00, 0x03, 0x13}));
}

TEST(HwsimDepth, FuncAndWriteMask) {
    Framebuffer fb(4, 4);
    Pipeline pipe(fb, findProfile("ideal"));
    pipe.state.depth = {true, CompareFunc::Less, true};
    pipe.drawRect(0, 0, 4, 4, 0.5f, Flat{});
    pipe.drawRect(0, 0, 4, 2, 0.5f, Flat{});  // equal depth fails LESS
    EXPECT_EQ(pipe.counts().samplesPassed, 16);
    EXPECT_EQ(pipe.counts().rejected[int(Stage::DepthEarly)], 8);
    pipe.state.depth = {true, CompareFunc::Greater, false};
    pipe.drawRect(0, 0, 2, 4, 0.75f, Flat{});
    EXPECT_EQ(pipe.counts().samplesPassed, 24);
    EXPECT_EQ(fb.depth[fb.index(0, 0)], 0.5f);  // write mask off
    pipe.state.depth.enabled = false;           // disabled: passes, never writes
    pipe.drawRect(0, 0, 4, 4, 0.1f, Flat{});
    EXPECT_EQ(pipe.counts().samplesPassed, 40);
    EXPECT_EQ(fb.depth[fb.index(3, 3)], 0.5f);
}

struct WriteDepth {
    void operator()(const Fragment& f, FragmentOutput& o) const { o.depth = f.x < 2 ? 0.25f : 0.75f; }
};

TEST(HwsimProgram, WrittenDepthIsTestedLate) {
    Framebuffer fb(4, 4);
    Pipeline pipe(fb, findProfile("ideal"));
    pipe.clearDepth(0.5f);
    pipe.state.depth = {true, CompareFunc::Less, true};
    pipe.drawRect(0, 0, 4, 4, 0.0f, WriteDepth{}, {.writesDepth = true});
    EXPECT_EQ(pipe.counts().invocations, 16);
    EXPECT_EQ(pipe.counts().rejected[int(Stage::DepthLate)], 8);
    EXPECT_EQ(pipe.counts().samplesPassed, 8);
    EXPECT_EQ(fb.depth[fb.index(0, 0)], 0.25f);
    EXPECT_EQ(fb.depth[fb.index(3, 0)], 0.5f);
}

struct DiscardOdd {
    void operator()(const Fragment& f, FragmentOutput& o) const { o.discard = (f.x & 1) != 0; }
};

TEST(HwsimProgram, DiscardKeepsEarlyTestButWritesOnlySurvivors) {
    Framebuffer fb(4, 4);
    Pipeline pipe(fb, findProfile("ideal"));
    pipe.state.depth = {true, CompareFunc::Less, true};
    pipe.drawRect(0, 0, 4, 2, 0.5f, Flat{});
    pipe.drawRect(0, 0, 4, 4, 0.25f, DiscardOdd{}, {.mayDiscard = true});
    EXPECT_EQ(pipe.counts().invocations, 8 + 16);
    EXPECT_EQ(pipe.counts().discarded, 8);
    EXPECT_EQ(pipe.counts().samplesPassed, 8 + 8);
    EXPECT_EQ(fb.depth[fb.index(0, 0)], 0.25f);
    EXPECT_EQ(fb.depth[fb.index(1, 0)], 0.5f);  // discarded: no depth write
}

TEST(HwsimProgram, EarlyFragmentTestsRunBeforeSideEffects) {
    Framebuffer fb(4, 4);
    Pipeline pipe(fb, findProfile("ideal"));
    pipe.clearDepth(0.5f);
    pipe.state.depth = {true, CompareFunc::Less, false};
    pipe.drawRect(0, 0, 4, 4, 0.75f, Flat{}, {.sideEffects = true});
    EXPECT_EQ(pipe.counts().invocations, 16);  // side effects: tests after the program
    EXPECT_EQ(pipe.counts().rejected[int(Stage::DepthLate)], 16);
    pipe.drawRect(0, 0, 4, 4, 0.75f, Flat{}, {.sideEffects = true, .earlyFragmentTests = true});
    EXPECT_EQ(pipe.counts().invocations, 16);
    EXPECT_EQ(pipe.counts().rejected[int(Stage::DepthEarly)], 16);
}

TEST(HwsimShading, QuadsRunHelperInvocations) {
    const Vertex tiny[3] = {{2.2f, 2.2f, 0}, {2.8f, 2.2f, 0}, {2.5f, 2.8f, 0}};  // covers pixel (2, 2) only
    Framebuffer fb(8, 8);
    Pipeline quad(fb, findProfile("modern-desktop"));
    quad.drawTriangle(tiny, Flat{});
    EXPECT_EQ(quad.counts().generated, 1);
    EXPECT_EQ(quad.counts().invocations, 4);
    EXPECT_EQ(quad.counts().helpers, 3);
    Pipeline pixel(fb, findProfile("ideal"));
    pixel.drawTriangle(tiny, Flat{});
    EXPECT_EQ(pixel.counts().invocations, 1);
    EXPECT_EQ(pixel.counts().helpers, 0);
}

TEST(HwsimShading, LockStepCostIsLanesTimesLongestPath) {
    auto branchy = [](const Fragment& f, FragmentOutput& o) { o.cost = (f.x == 0 && f.y == 0) ? 10 : 1; };
    Framebuffer fb(16, 16);
    Pipeline pixel(fb, findProfile("ideal"));
    pixel.drawRect(0, 0, 16, 16, 0, branchy);
    EXPECT_EQ(pixel.counts().cost, 255 + 10);
    Pipeline warp(fb, findProfile("modern-desktop"));  // 8x4 lanes in lock step
    warp.drawRect(0, 0, 16, 16, 0, branchy);
    EXPECT_EQ(warp.counts().cost, 32 * 10 + (256 - 32));
}

Profile statistics(int stampW, int stampH, bool atScan) {
    Profile p = findProfile("mesa-llvmpipe");
    p.statsStampW = stampW, p.statsStampH = stampH, p.statsCountedAtScan = atScan;
    return p;
}

std::int64_t shaderInvocationsOf(const Profile& profile, float depth) {
    Framebuffer fb(16, 16, 0.5f);
    Pipeline pipe(fb, profile);
    pipe.state.depth = {true, CompareFunc::Less, true};
    pipe.drawRect(1, 1, 5, 5, depth, Flat{});  // 16 pixels over 9 quads and 4 stamps of 4x4
    return pipe.counts().fragmentShaderInvocations;
}

TEST(HwsimStatistics, ShaderInvocationsCountPixelsQuadsOrStamps) {
    EXPECT_EQ(shaderInvocationsOf(statistics(1, 1, false), 0.25f), 16);
    EXPECT_EQ(shaderInvocationsOf(statistics(2, 2, false), 0.25f), 9 * 4);
    EXPECT_EQ(shaderInvocationsOf(statistics(4, 4, false), 0.25f), 4 * 16);
    EXPECT_EQ(shaderInvocationsOf(statistics(4, 4, false), 0.75f), 0);       // all rejected before the program
    EXPECT_EQ(shaderInvocationsOf(statistics(4, 4, true), 0.75f), 4 * 16);   // counted where coverage is found
    EXPECT_EQ(shaderInvocationsOf(statistics(1, 1, true), 0.75f), 16);
}

TEST(HwsimStatistics, ClippingCountsTrianglesAndMayDropZeroArea) {
    const Vertex flat[3] = {{1, 1, 0}, {5, 1, 0}, {3, 1, 0}};
    const Vertex real[3] = {{1, 1, 0}, {5, 1, 0}, {3, 5, 0}};
    for (bool dropsZeroArea : {false, true}) {
        Profile profile = findProfile("ideal");
        profile.clippingOutputSkipsZeroArea = dropsZeroArea;
        Framebuffer fb(8, 8);
        Pipeline pipe(fb, profile);
        pipe.drawTriangle(flat, Flat{});
        pipe.drawTriangle(real, Flat{});
        EXPECT_EQ(pipe.counts().clippingInputPrimitives, 2);
        EXPECT_EQ(pipe.counts().clippingOutputPrimitives, dropsZeroArea ? 1 : 2);
    }
}

TEST(HwsimBlend, AddsAndMasks) {
    Framebuffer fb(2, 2);
    Pipeline pipe(fb, findProfile("ideal"));
    pipe.state.blend = {true, BlendFactor::One, BlendFactor::One};
    pipe.state.colorMask = {true, false, true, true};
    auto half = [](const Fragment&, FragmentOutput& o) { o.color = {0.5f, 0.5f, 0.25f, 1}; };
    pipe.drawRect(0, 0, 2, 2, 0, half);
    pipe.drawRect(0, 0, 2, 2, 0, half);
    EXPECT_EQ(fb.color[0], 1.0f);
    EXPECT_EQ(fb.color[1], 0.0f);
    EXPECT_EQ(fb.color[2], 0.5f);
    pipe.state.blend = {true, BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha};
    pipe.drawRect(0, 0, 2, 2, 0, [](const Fragment&, FragmentOutput& o) { o.color = {0, 0, 0, 0.25f}; });
    EXPECT_EQ(fb.color[0], 0.75f);
}

// A GL_R32F target keeps the red channel only; a fetch of it reads
// (r, 0, 0, 1), and blend factors see that alpha of 1.
TEST(HwsimBlend, OneChannelTargetsKeepRedAndReadAlphaAsOne) {
    Framebuffer fb(2, 2, 1.0f, 1);
    ASSERT_EQ(fb.color.size(), 4u);
    Pipeline pipe(fb, findProfile("ideal"));
    pipe.drawRect(0, 0, 2, 2, 0, [](const Fragment&, FragmentOutput& o) { o.color = {0.5f, 0.25f, 0.125f, 0}; });
    EXPECT_EQ(fb.color[3], 0.5f);
    EXPECT_EQ(fb.texel(3), (std::array<float, 4>{0.5f, 0, 0, 1}));
    pipe.state.blend = {true, BlendFactor::One, BlendFactor::One};
    pipe.drawRect(0, 0, 2, 2, 0, [](const Fragment&, FragmentOutput& o) { o.color = {0.25f, 9, 9, 9}; });
    EXPECT_EQ(fb.color[0], 0.75f);
    pipe.state.blend = {true, BlendFactor::Zero, BlendFactor::DstAlpha};  // keeps the stored red times 1
    pipe.drawRect(0, 0, 2, 2, 0, [](const Fragment&, FragmentOutput& o) { o.color = {0.5f, 0, 0, 0}; });
    EXPECT_EQ(fb.color[0], 0.75f);
    pipe.state.colorMask = {false, true, true, true};  // no channel of this target: nothing written
    pipe.state.blend = {};
    pipe.drawRect(0, 0, 2, 2, 0, [](const Fragment&, FragmentOutput& o) { o.color = {0, 0, 0, 0}; });
    EXPECT_EQ(fb.color[0], 0.75f);
    EXPECT_THROW(Framebuffer(2, 2, 1.0f, 5), std::invalid_argument);
}

TEST(HwsimQuery, CountsSamplesPassedBetweenBeginAndEnd) {
    Framebuffer fb(8, 8);
    Pipeline pipe(fb, findProfile("ideal"));
    pipe.state.depth = {true, CompareFunc::Less, true};
    pipe.drawRect(0, 0, 8, 8, 0.5f, Flat{});
    pipe.beginQuery();
    pipe.drawRect(0, 0, 8, 4, 0.25f, Flat{});
    pipe.drawRect(0, 0, 8, 8, 0.75f, Flat{});
    EXPECT_EQ(pipe.endQuery(), 32);
}

TEST(HwsimCoarse, WholeTilesAreCulledBeforeTheProgram) {
    Framebuffer fb(32, 32);
    Pipeline pipe(fb, findProfile("geforce-7800"));
    pipe.state.depth = {true, CompareFunc::Less, true};
    pipe.drawRect(0, 0, 12, 32, 0.25f, Flat{});  // columns 0..11 nearer
    pipe.resetCounts();
    pipe.drawRect(4, 0, 32, 32, 0.5f, Flat{});   // 8x8 tiles: column 0 culled, column 1 mixed
    const StageCounts& c = pipe.counts();
    EXPECT_EQ(c.tilesCulled, 4);
    EXPECT_EQ(c.rejected[int(Stage::DepthEarly)], 4 * 4 * 8);
    EXPECT_EQ(c.rejected[int(Stage::DepthLate)], 4 * 4 * 8);  // mixed tiles: after the program
    EXPECT_EQ(c.invocations, 28 * 32 - 4 * 4 * 8);
    EXPECT_EQ(c.samplesPassed, 20 * 32);
}

TEST(HwsimCoarse, DirectionChangeLosesHierarchicalZUntilClear) {
    Framebuffer fb(16, 16);
    Pipeline pipe(fb, findProfile("modern-desktop"));
    pipe.state.depth = {true, CompareFunc::Less, true};
    pipe.drawRect(0, 0, 16, 16, 0.25f, Flat{});
    pipe.state.depth.func = CompareFunc::Greater;
    pipe.drawRect(0, 0, 16, 16, 0.1f, Flat{});
    pipe.state.depth.func = CompareFunc::Less;
    pipe.drawRect(0, 0, 16, 16, 0.5f, Flat{});
    EXPECT_EQ(pipe.counts().tilesCulled, 0);
    EXPECT_EQ(pipe.counts().rejected[int(Stage::DepthEarly)], 512);  // per-pixel early tests still run
    pipe.clearDepth(0.25f);
    pipe.drawRect(0, 0, 16, 16, 0.5f, Flat{});
    EXPECT_EQ(pipe.counts().tilesCulled, 4);
}

TEST(HwsimBounds, ChangingBoundsLosesTheEarlyTestOnGeforce7800) {
    Framebuffer fb(16, 16);
    Pipeline pipe(fb, findProfile("geforce-7800"));
    pipe.clearDepth(0.75f);
    pipe.state.bounds = {true, 0, 0.5f};
    pipe.drawRect(0, 0, 16, 16, 0, Flat{});
    EXPECT_EQ(pipe.counts().invocations, 0);
    EXPECT_EQ(pipe.counts().tilesCulled, 4);
    pipe.state.bounds = {true, 0, 0.25f};
    pipe.drawRect(0, 0, 16, 16, 0, Flat{});
    EXPECT_EQ(pipe.counts().invocations, 256);
    EXPECT_EQ(pipe.counts().rejected[int(Stage::Bounds)], 512);
}

}  // namespace
}  // namespace weft::hwsim

namespace weft::hwsim {
namespace {

// Overlapping triangles around the centre of a 300x200 target, at varied depths.
std::vector<std::array<Vertex, 3>> fan(int count) {
    std::vector<std::array<Vertex, 3>> t;
    for (int i = 0; i < count; ++i) {
        const float a = float(i) * 0.7f;
        t.push_back({Vertex{150 + 180 * std::cos(a), 100 + 150 * std::sin(a), 0.02f * float(i % 7)},
                     Vertex{150 + 160 * std::cos(a + 2.2f), 100 + 140 * std::sin(a + 2.2f), 0.5f},
                     Vertex{150 + 170 * std::cos(a + 4.1f), 100 + 130 * std::sin(a + 4.1f), 0.9f}});
    }
    return t;
}

// One draw call of many triangles is binned by screen tiles; every pixel must
// still see the triangles in order (the blend below is order-dependent), and
// the program must see each one's index as gl_PrimitiveID.
TEST(HwsimPipeline, OneDrawCallOfManyTrianglesEqualsOneDrawPerTriangle) {
    const auto triangles = fan(40);
    auto program = [](const Fragment& f, FragmentOutput& o) {
        o.color = {float(f.primitive) / 64.0f, f.z, 0, 0.5f};
        o.cost = 1 + f.primitive % 3;
    };
    auto setUp = [](Pipeline& pipe) {
        pipe.state.depth = {true, CompareFunc::LessEqual, true};
        pipe.state.blend = {true, BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha};
    };
    for (const Profile& pr : builtinProfiles()) {
        const std::string& profile = pr.name;
        Framebuffer oneFb(300, 200), manyFb(300, 200);
        Pipeline one(oneFb, findProfile(profile)), many(manyFb, findProfile(profile));
        setUp(one), setUp(many);
        one.drawTriangles(triangles, program);
        for (std::size_t i = 0; i < triangles.size(); ++i) {
            const Vertex v[3] = {triangles[i][0], triangles[i][1], triangles[i][2]};
            many.drawTriangle(v, [&](const Fragment& f, FragmentOutput& o) {
                Fragment g = f;
                g.primitive = int(i);
                program(g, o);
            });
        }
        EXPECT_EQ(one.counts().named(), many.counts().named()) << profile;
        EXPECT_EQ(oneFb.color, manyFb.color) << profile;
        EXPECT_EQ(oneFb.depth, manyFb.depth) << profile;
        EXPECT_EQ(one.counts().clippingInputPrimitives, 40) << profile;
        EXPECT_GT(one.counts().generated, 50000) << profile;
        float highest = 0;  // the last triangles drawn must show through somewhere
        for (std::size_t i = 0; i < oneFb.color.size(); i += 4) highest = std::max(highest, oneFb.color[i]);
        EXPECT_GT(highest, 0.25f) << profile;
    }
}

// Where the early tests are a depth test alone, tiles are depth-tested row by
// row before any program runs. A program that may discard (but does not)
// keeps the per-quad order of tests where the profile keeps such programs'
// tests early (deferring their writes); both must count the same.
TEST(HwsimPipeline, DepthTestedRowsCountAsDepthTestedQuads) {
    const auto triangles = fan(40);
    int compared = 0;
    for (const Profile& pr : builtinProfiles()) {
        const std::string& profile = pr.name;
        Framebuffer probeFb(8, 8);
        Pipeline probe(probeFb, pr);
        probe.state.depth = {true, CompareFunc::Less, true};
        if (!probe.plan({.mayDiscard = true}).zsEarly) continue;  // discard moves its tests late there
        ++compared;
        auto render = [&](bool mayDiscard) {
            Framebuffer fb(300, 200);
            Pipeline pipe(fb, findProfile(profile));
            pipe.state.depth = {true, CompareFunc::Less, true};
            const ProgramTraits traits{.mayDiscard = mayDiscard};
            pipe.drawTriangles(triangles, [](const Fragment& f, FragmentOutput& o) { o.color = {f.z, 0, 0, 1}; }, traits);
            return std::make_pair(pipe.counts().named(), fb.depth);
        };
        const auto [rows, rowDepth] = render(false);
        const auto [quads, quadDepth] = render(true);
        EXPECT_EQ(rows, quads) << profile;
        EXPECT_EQ(rowDepth, quadDepth) << profile;
        EXPECT_GT(rows.at("fragments.rejected.depth_early") + rows.at("fragments.rejected.depth_late"), 1000) << profile;
    }
    EXPECT_GE(compared, 1);
    Framebuffer fb(8, 8);
    Pipeline llvmpipe(fb, findProfile("mesa-llvmpipe"));
    llvmpipe.state.depth = {true, CompareFunc::Less, true};
    EXPECT_TRUE(llvmpipe.plan({}).depthFirst);  // the two renders above took both paths
    EXPECT_FALSE(llvmpipe.plan({.mayDiscard = true}).depthFirst);
}

// A flat program (ProgramTraits::flat) runs once per primitive and tile
// where the plan allows; every count and buffer must equal running it per
// lane, under every profile, unblended and added, stippled or not.
TEST(HwsimPipeline, FlatProgramsCountAsProgramsRunPerLane) {
    const auto triangles = fan(40);
    auto program = [](const Fragment& f, FragmentOutput& o) {
        o.color = {float(f.primitive % 5) / 4.0f, 0.5f, 0, 1};
        o.cost = 1 + f.primitive % 3;
    };
    int flatPlans = 0;
    for (const Profile& pr : builtinProfiles())
        for (const bool add : {false, true})
            for (const bool stipple : {false, true}) {
                if (stipple && !pr.polygonStipple) continue;
                auto render = [&](bool flat) {
                    Framebuffer fb(300, 200);
                    Pipeline pipe(fb, pr);
                    pipe.state.depth = {true, CompareFunc::Less, true};
                    if (add) pipe.state.blend = {true, BlendFactor::One, BlendFactor::One};
                    if (stipple) pipe.state.stipple = {true, StippleState::interleaved(4, 1, 2)};
                    flatPlans += flat && pipe.plan({.flat = true}).flat;
                    pipe.drawTriangles(triangles, program, {.flat = flat});
                    return std::make_pair(pipe.counts().named(), fb);
                };
                const auto [perLane, perLaneFb] = render(false);
                const auto [flat, flatFb] = render(true);
                const std::string what = pr.name + (add ? " added" : " replaced") + (stipple ? " stippled" : "");
                EXPECT_EQ(perLane, flat) << what;
                EXPECT_EQ(perLaneFb.color, flatFb.color) << what;
                EXPECT_EQ(perLaneFb.depth, flatFb.depth) << what;
                EXPECT_GT(perLane.at("fragment_program.invocations"), 1000) << what;
            }
    EXPECT_GE(flatPlans, 4);  // llvmpipe, at least, took the flat path in every case
    Framebuffer odd(301, 200);
    Pipeline llvmpipe(odd, findProfile("mesa-llvmpipe"));
    llvmpipe.state.depth = {true, CompareFunc::Less, true};
    EXPECT_FALSE(llvmpipe.plan({.flat = true}).flat);  // a quad lane past the edge: per lane
    EXPECT_FALSE(llvmpipe.plan({.mayDiscard = true, .flat = true}).flat);
}

// Counts and buffers do not depend on how tiles were spread over threads.
TEST(HwsimPipeline, ThreadedAndSerialDrawsAgree) {
    auto render = [](bool parallel, const char* profile) {
        Framebuffer fb(300, 200);
        Pipeline pipe(fb, findProfile(profile));
        pipe.setParallel(parallel);
        pipe.state.depth = {true, CompareFunc::LessEqual, true};
        pipe.state.stencil = {true, CompareFunc::Always, 1, 0xff, 0xff, StencilOp::Keep, StencilOp::Keep, StencilOp::IncrWrap};
        pipe.state.blend = {true, BlendFactor::One, BlendFactor::One};
        for (int i = 0; i < 40; ++i) {
            const float a = float(i) * 0.7f;
            const Vertex v[3] = {{150 + 180 * std::cos(a), 100 + 150 * std::sin(a), 0.02f * float(i % 7)},
                                 {150 + 160 * std::cos(a + 2.2f), 100 + 140 * std::sin(a + 2.2f), 0.5f},
                                 {150 + 170 * std::cos(a + 4.1f), 100 + 130 * std::sin(a + 4.1f), 0.9f}};
            pipe.drawTriangle(v, [](const Fragment& f, FragmentOutput& o) {
                o.color = {f.z, 1, 0, 1};
                o.discard = (f.x * 7 + f.y * 3) % 11 == 0;
                o.cost = 1 + (f.x & 3);
            }, {.mayDiscard = true});
        }
        return std::make_pair(pipe.counts().named(), fb);
    };
    for (const char* profile : {"ideal", "geforce-7800", "modern-desktop"}) {
        const auto [serialCounts, serialFb] = render(false, profile);
        const auto [parallelCounts, parallelFb] = render(true, profile);
        EXPECT_EQ(serialCounts, parallelCounts) << profile;
        EXPECT_EQ(serialFb.color, parallelFb.color) << profile;
        EXPECT_EQ(serialFb.depth, parallelFb.depth) << profile;
        EXPECT_EQ(serialFb.stencil, parallelFb.stencil) << profile;
        EXPECT_GT(serialCounts.at("fragments.generated"), 50000) << profile;
    }
}

}  // namespace
}  // namespace weft::hwsim
