#pragma once
// The modelled GL fragment pipeline. A draw scans a primitive in screen
// tiles of 2x2 quads and runs each covered pixel through small stage units
// in GL order:
//   rasterizer: coverage (fragments.generated), polygon stipple, scissor
//   coarse:     hierarchical depth / stencil / bounds culling of whole tiles
//   early:      depth bounds, stencil, depth (when the profile and program allow)
//   program:    the fragment program, per pixel or per 2x2 quad with helpers
//   late:       stipple (when late), bounds, stencil, depth, occlusion query,
//               blending and writes
// The fragment program is any callable `void(const Fragment&, FragmentOutput&)`,
// a template parameter, so the per-fragment loop has no virtual call and no
// allocation. Programs may be called concurrently for different pixels.
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <span>
#include <vector>

#include "hwsim/counts.hpp"
#include "hwsim/framebuffer.hpp"
#include "hwsim/gl_state.hpp"
#include "hwsim/profile.hpp"
#include "hwsim/raster.hpp"
#include "hwsim/tile_masks.hpp"

namespace weft::hwsim {

// What the pipeline must know of a program to place the tests around it.
struct ProgramTraits {
    bool writesDepth = false;         // gl_FragDepth
    bool mayDiscard = false;          // discard / kill
    bool sideEffects = false;         // image, buffer or atomic-counter writes
    bool earlyFragmentTests = false;  // layout(early_fragment_tests)
    bool readsPosition = false;       // gl_FragCoord (matters only to a profile quirk)
    // Flat shading: the program's outputs and cost depend on the primitive
    // alone (not on the fragment's position, depth or helper state) and it
    // never discards. Where the plan allows (DrawPlan::flat) it then runs
    // once per primitive and tile and its result stands for every lane;
    // every count is the same as running it per lane.
    bool flat = false;
};

struct Fragment {
    int x, y;
    float z;      // interpolated window depth
    bool helper;  // runs only to complete a 2x2 quad; its results are dropped
    int primitive = 0;  // gl_PrimitiveID: the triangle's index within its draw call
};

struct FragmentOutput {
    std::array<float, 4> color{0, 0, 0, 1};
    float depth = 0;       // read when the program writes depth
    bool discard = false;
    int cost = 1;          // length of the path this invocation took (branch cost model)
};

// A program whose outputs go to storage of the caller's (further render
// targets, as a multi-target program writes them): `write` runs for every
// fragment that passes all tests, where the pipeline writes colour; a
// fragment rejected after the program leaves no trace, as on hardware.
template <class Shade, class Write>
struct ProgramWithWrites {
    Shade shade;
    Write write;
    void operator()(const Fragment& f, FragmentOutput& o) const { shade(f, o); }
    void writeOutputs(const Fragment& f, const FragmentOutput& o) const { write(f, o); }
};
template <class Shade, class Write>
ProgramWithWrites<Shade, Write> withWrites(Shade shade, Write write) {
    return {std::move(shade), std::move(write)};
}

// Where each stage runs for one draw; made once per draw from the state,
// the profile and the program's traits.
struct DrawPlan {
    bool stipple = false, stippleStart = false, stippleLate = false, stippleMirrored = false, scissor = false;
    bool bounds = false, boundsEarly = false;
    bool stencil = false, depth = false, zsEarly = false, zsLate = false, deferWrites = false;
    bool depthWrites = false, stencilWrites = false, writesDepth = false, colorWrites = false;
    bool colorReplace = false, colorAdd = false;  // every channel written: unblended, or blended ONE + ONE (the common cases)
    bool coarse = false, coarseDepth = false, coarseStencil = false, coarseBounds = false;
    bool quad = false;
    bool countEarly = false;
    bool emptyQuadsRun = false;  // quads emptied by early tests still run (profile quirk)
    bool simple = false;  // per-pixel programs, at most an early depth test: the short path
    // The early tests are a depth test alone, and nothing after them reads
    // the depth buffer: each tile's pixel rows are depth-tested in one sweep
    // before any program runs (a primitive covers a pixel once, so the order
    // within the tile cannot matter).
    bool depthFirst = false;
    // A flat program (ProgramTraits::flat) on the depthFirst path, into a
    // target of even size (no quad lane past its edge) with every colour
    // channel written or none: a tile's lanes are counted and written from
    // its row masks, the program run once (Pipeline::shadeFlatTile).
    bool flat = false;
    int tileW = 16, tileH = 16, blockW = 1, blockH = 1, coarseTile = 0;
    bool wholeBlock = false;  // a lock-step block that runs costs all its lanes (fixed-width SIMD)
    int stampW = 1, stampH = 1;  // the profile's FRAGMENT_SHADER_INVOCATIONS stamp
    bool statsAtScan = false;    // stamps counted where coverage is found, not where the program runs
};

class Pipeline {
public:
    Pipeline(Framebuffer& fb, const Profile& profile) : fb_(fb), profile_(profile) {}

    PipelineState state;

    // A depth clear starts a new frame for the profile's "within a frame" rules.
    void clearDepth(float value = 1.0f);
    void clearStencil(std::uint8_t value = 0);
    void clearColor(std::array<float, 4> value = {0, 0, 0, 0});

    template <class Program>
    void drawTriangle(const Vertex (&v)[3], Program&& program, ProgramTraits traits = {}) {
        draw(profile_.floatSpans ? setupTriangleSpans(v, fb_.width, fb_.height, spans_)
                                 : setupTriangle(v, profile_.fillRule, fb_.width, fb_.height),
             program, traits);
    }
    // One draw call of many triangles (glDrawArrays(GL_TRIANGLES)); the program
    // sees each one's index as Fragment::primitive. The work is binned by
    // screen tiles, each bin taking the triangles in draw order, so every
    // pixel sees them in GL's order while the bin's part of the framebuffer
    // stays in cache across triangles (as tiled rasterizers do). Counts equal
    // those of one drawTriangle per triangle.
    template <class Program>
    void drawTriangles(std::span<const std::array<Vertex, 3>> triangles, Program&& program, ProgramTraits traits = {});
    // GL_QUADS: the triangles (0, 1, 2) and (0, 2, 3).
    template <class Program>
    void drawQuad(const Vertex (&v)[4], Program&& program, ProgramTraits traits = {}) {
        const Vertex a[3] = {v[0], v[1], v[2]}, b[3] = {v[0], v[2], v[3]};
        drawTriangle(a, program, traits);
        drawTriangle(b, program, traits);
    }
    template <class Program>
    void drawRect(int x0, int y0, int x1, int y1, float z, Program&& program, ProgramTraits traits = {}) {
        draw(setupRect(x0, y0, x1, y1, z, fb_.width, fb_.height), program, traits);
    }

    // SAMPLES_PASSED between begin and end.
    void beginQuery() { queryStart_ = counts_.samplesPassed; }
    std::int64_t endQuery() const { return counts_.samplesPassed - queryStart_; }

    const StageCounts& counts() const { return counts_; }
    void resetCounts() { counts_ = StageCounts{}; }
    Framebuffer& framebuffer() { return fb_; }
    const Profile& profile() const { return profile_; }
    void setParallel(bool on) { parallel_ = on; }
    // The plan the next draw with these traits would use (tests, documentation).
    DrawPlan plan(const ProgramTraits& traits);

private:
    template <class Program>
    void draw(const PrimitiveSetup& s, Program& program, const ProgramTraits& traits);
    void countPrimitive(const PrimitiveSetup& s);
    // Every tile of every primitive through scanTile, binned by screen tiles
    // (the primitives' order kept within each bin), counts added.
    template <class Program>
    void scanBinned(std::span<const PrimitiveSetup> setups, Program& program, const DrawPlan& p);
    template <class Program>
    void scanTile(const PrimitiveSetup& s, Program& program, const DrawPlan& p, int tx0, int ty0, StageCounts& c) const;
    // Coverage, stipple and scissor of the tile's pixel rows ty0 .. ty0 + rowCount - 1
    // (counted); `live` receives the survivors, `scanned` the covered pixels inside
    // the scissor. Returns the survivors' number.
    int scanRows(const PrimitiveSetup& s, const DrawPlan& p, bool full, int tx0, int ty0, int x0, int y0, int x1, int y1,
                 int rowCount, std::uint64_t* live, std::uint64_t* scanned, StageCounts& c) const;
    // The depth test of the live pixels of rows ty0 .. ty0 + rowCount - 1,
    // columns [x0, x1) (DrawPlan::depthFirst); `live` keeps the passing ones.
    void depthTestRows(const PrimitiveSetup& s, const DrawPlan& p, int tx0, int ty0, int x0, int x1, int rowCount,
                       std::uint64_t* live, StageCounts& c) const;
    void cullCoarseTiles(const PrimitiveSetup& s, const DrawPlan& p, int tx0, int ty0, int y1, int x1,
                         std::uint8_t* masks, StageCounts& c) const;
    // The programs, counts and writes of a tile's depth-tested live rows
    // for a flat program (DrawPlan::flat), as the quads of scanTile count them.
    template <class Program>
    void shadeFlatTile(const PrimitiveSetup& s, Program& program, const DrawPlan& p, int tx0, int ty0, int rowCount,
                       const std::uint64_t* live, StageCounts& c) const;
    // Both return the lanes whose program ran for the fragment (not as a helper).
    template <class Program>
    unsigned shadePixels(const PrimitiveSetup& s, Program& program, const DrawPlan& p, int qx, int qy, unsigned mask,
                         StageCounts& c) const;
    // shadeQuad after the tile's rows were depth-tested (DrawPlan::depthFirst):
    // no test is left, only the program and the writes.
    template <class Program>
    unsigned shadeTestedQuad(const PrimitiveSetup& s, Program& program, const DrawPlan& p, int qx, int qy, unsigned mask,
                             StageCounts& c, std::int64_t* blockMax, std::int64_t* blockLanes) const;
    template <class Program>
    unsigned shadeQuad(const PrimitiveSetup& s, Program& program, const DrawPlan& p, int qx, int qy, unsigned mask,
                   StageCounts& c, std::int64_t* blockMax, std::int64_t* blockLanes) const;

    // Stencil then depth at one pixel; Stage::Count when both pass. Writes
    // the updates unless `pending` is given, which then receives them.
    struct Pending {
        bool stencil = false, depth = false;
        std::uint8_t stencilValue = 0;
        float depthValue = 0;
    };
    Stage stencilDepth(std::size_t idx, float z, const DrawPlan& p, bool early, Pending* pending) const;
    void applyPending(std::size_t idx, const Pending& pending) const;
    bool inBounds(std::size_t idx) const {
        const float d = fb_.depth[idx];
        return d >= state.bounds.zmin && d <= state.bounds.zmax;
    }
    bool stippleKeeps(int x, int y) const { return (state.stipple.rows[y & 31] >> (x & 31)) & 1u; }
    bool stippleKeeps(int x, int y, bool mirrored) const { return stippleKeeps(x, mirrored ? fb_.height - 1 - y : y); }
    // The kept bits of mask; adds the dropped ones to a rejection count.
    static std::uint64_t keep(std::uint64_t mask, std::uint64_t kept, std::int64_t& rejected) {
        rejected += bitCount(mask & ~kept);
        return mask & kept;
    }
    // Whether every covered fragment of the tile fails a coarse test; which.
    bool coarseReject(const PrimitiveSetup& s, const DrawPlan& p, int tx0, int ty0, int tx1, int ty1, Stage& stage) const;
    void writeColor(std::size_t idx, const std::array<float, 4>& src, const DrawPlan& p) const;

    Framebuffer& fb_;
    const Profile& profile_;
    StageCounts counts_;
    std::int64_t queryStart_ = 0;
    bool parallel_ = true;
    // Frame history for the profile's rules (reset by clearDepth).
    int frameDirection_ = 0;
    bool coarseLost_ = false;
    bool frameBoundsSet_ = false, boundsLost_ = false;
    float frameBounds_[2] = {0, 0};
    SpanRows spans_;  // reused by every float-span triangle
};

}  // namespace weft::hwsim

#include "hwsim/pipeline_scan.hpp"
