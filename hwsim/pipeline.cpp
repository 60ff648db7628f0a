#include "hwsim/pipeline.hpp"

#include <limits>

namespace weft::hwsim {

namespace {

// A clear of a whole plane, in parallel slabs: a replay clearing depth before
// each of its passes would otherwise spend a serial memory sweep on each.
template <class Plane, class Value>
void fillPlane(Plane& plane, const Value& value, bool parallel) {
    constexpr std::size_t kSlab = std::size_t(1) << 16;
    if (!parallel || plane.size() < 4 * kSlab) return std::fill(plane.begin(), plane.end(), value);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, plane.size(), kSlab), [&](const tbb::blocked_range<std::size_t>& r) {
        std::fill(plane.begin() + std::ptrdiff_t(r.begin()), plane.begin() + std::ptrdiff_t(r.end()), value);
    });
}

}  // namespace

void Pipeline::clearDepth(float value) {
    fillPlane(fb_.depth, value, parallel_);
    frameDirection_ = 0, coarseLost_ = false, frameBoundsSet_ = false, boundsLost_ = false;
}
void Pipeline::clearStencil(std::uint8_t value) { fillPlane(fb_.stencil, value, parallel_); }
void Pipeline::clearColor(std::array<float, 4> value) {
    if (fb_.channels == 1) return fillPlane(fb_.color, value[0], parallel_);
    for (std::size_t i = 0; i < fb_.color.size(); ++i) fb_.color[i] = value[i % std::size_t(fb_.channels)];
}

namespace {

bool writesStencil(const StencilState& s) {
    return s.enabled && s.writeMask != 0 &&
           (s.sfail != StencilOp::Keep || s.dpfail != StencilOp::Keep || s.dppass != StencilOp::Keep);
}

bool discardForcesLate(DiscardRule rule, bool depthWrites, bool stencilWrites) {
    switch (rule) {
        case DiscardRule::Never: return false;
        case DiscardRule::Always: return true;
        case DiscardRule::WithStencilWrites: return stencilWrites;
        case DiscardRule::WithDepthOrStencilWrites: return depthWrites || stencilWrites;
    }
    return true;
}

}  // namespace

// Frame history first (it changes what later draws may do), then the plan.
DrawPlan Pipeline::plan(const ProgramTraits& t) {
    const Profile& pr = profile_;
    DrawPlan p;
    p.stipple = state.stipple.enabled;
    if (p.stipple) pr.require(pr.polygonStipple, "polygon stipple", "this pass");
    p.stippleStart = p.stipple && pr.stipple == StipplePosition::ProgramStart;
    p.stippleLate = p.stipple && pr.stipple == StipplePosition::Late;
    p.stippleMirrored = pr.stippleMirroredWithPosition && t.readsPosition;
    p.scissor = state.scissor.enabled;
    p.bounds = state.bounds.enabled;
    if (p.bounds) {
        pr.require(pr.bounds != BoundsSupport::Unsupported, "the depth bounds test (EXT_depth_bounds_test)", "this pass");
        const bool same = frameBounds_[0] == state.bounds.zmin && frameBounds_[1] == state.bounds.zmax;
        if (frameBoundsSet_ && !same) boundsLost_ = true;
        frameBoundsSet_ = true, frameBounds_[0] = state.bounds.zmin, frameBounds_[1] = state.bounds.zmax;
    }
    p.depth = state.depth.enabled;
    p.stencil = state.stencil.enabled;
    if (p.depth) {
        const int dir = depthDirection(state.depth.func);
        if (dir != 0 && frameDirection_ != 0 && dir != frameDirection_) coarseLost_ = true;
        if (dir != 0) frameDirection_ = dir;
    }
    p.depthWrites = p.depth && state.depth.writeMask;
    p.stencilWrites = writesStencil(state.stencil);
    p.writesDepth = t.writesDepth;

    const bool mayKill = t.mayDiscard || p.stippleLate || p.stippleStart;
    const bool late = !t.earlyFragmentTests &&
                      (t.writesDepth || (t.sideEffects && pr.sideEffectsForceLate) ||
                       (mayKill && discardForcesLate(pr.discardForcesLate, p.depthWrites, p.stencilWrites)));
    const bool zs = p.depth || p.stencil;
    const bool perPixel = pr.earlyTests == EarlyTests::PerPixel && (!pr.earlyNeedsDepthTest || p.depth);
    p.zsEarly = zs && (t.earlyFragmentTests || (!late && perPixel));
    p.zsLate = zs && !p.zsEarly;
    p.deferWrites = p.zsEarly && mayKill && !t.earlyFragmentTests && (p.depthWrites || p.stencilWrites);
    const bool boundsMayBeEarly = p.bounds && pr.bounds == BoundsSupport::Early && !(pr.boundsChangeForcesLate && boundsLost_);
    p.boundsEarly = (boundsMayBeEarly && perPixel) || (p.bounds && pr.bounds == BoundsSupport::WithDepthTest && p.zsEarly);

    const bool coarseOk = pr.coarseTile > 0 && pr.earlyTests != EarlyTests::None;
    const bool stencilFailKeeps = !p.stencil || state.stencil.sfail == StencilOp::Keep;
    p.coarseBounds = coarseOk && boundsMayBeEarly;
    p.coarseStencil = coarseOk && !late && pr.coarseStencil && p.stencil && stencilFailKeeps;
    p.coarseDepth = coarseOk && !late && !coarseLost_ && p.depth && stencilFailKeeps &&
                    (!p.stencil || state.stencil.dpfail == StencilOp::Keep);
    p.coarse = p.coarseBounds || p.coarseStencil || p.coarseDepth;
    p.coarseTile = pr.coarseTile;

    p.countEarly = t.earlyFragmentTests && pr.queryCountsAtEarlyTests;
    p.emptyQuadsRun = pr.emptyQuadsStillRun && p.zsEarly && p.stencil;
    p.quad = pr.shading == ShadingGranularity::Quad;
    p.simple = !p.quad && pr.branchBlockW * pr.branchBlockH == 1 && !p.stencil && !p.bounds && !p.stippleLate && !p.stippleStart &&
               !p.deferWrites && !p.countEarly && !t.writesDepth && (!p.depth || p.zsEarly);
    p.depthFirst = !p.simple && p.zsEarly && p.depth && !p.stencil && !p.bounds && !p.stippleStart && !p.stippleLate && !p.deferWrites &&
                   !p.countEarly && !p.emptyQuadsRun && !p.coarse && !t.writesDepth;
    p.blockW = pr.branchBlockW, p.blockH = pr.branchBlockH, p.wholeBlock = pr.lockStepWholeBlock;
    bool anyChannel = false, everyChannel = true;  // of those the target has
    for (int ch = 0; ch < fb_.channels; ++ch) anyChannel |= state.colorMask[std::size_t(ch)], everyChannel &= state.colorMask[std::size_t(ch)];
    p.colorWrites = anyChannel;
    const BlendState& blend = state.blend;
    p.colorReplace = everyChannel && !blend.enabled;
    p.colorAdd = everyChannel && blend.enabled && blend.src == BlendFactor::One && blend.dst == BlendFactor::One;
    p.stampW = pr.statsStampW, p.stampH = pr.statsStampH, p.statsAtScan = pr.statsCountedAtScan;
    p.flat = t.flat && p.depthFirst && !t.mayDiscard && fb_.width % 2 == 0 && fb_.height % 2 == 0 &&
             (!p.colorWrites || p.colorReplace || p.colorAdd);
    p.tileW = std::max({16, pr.coarseTile, pr.branchBlockW});
    p.tileH = std::max({16, pr.coarseTile, pr.branchBlockH});
    return p;
}

namespace {

// Whether every stored value in [lo, hi] fails "incoming func stored" for
// every incoming value in [zlo, zhi].
bool rangeFails(CompareFunc f, float zlo, float zhi, float lo, float hi) {
    switch (f) {
        case CompareFunc::Never: return true;
        case CompareFunc::Less: return zlo >= hi;
        case CompareFunc::LessEqual: return zlo > hi;
        case CompareFunc::Greater: return zhi <= lo;
        case CompareFunc::GreaterEqual: return zhi < lo;
        case CompareFunc::Equal: return zhi < lo || zlo > hi;
        case CompareFunc::NotEqual: return zlo == zhi && lo == hi && zlo == lo;
        case CompareFunc::Always: return false;
    }
    return false;
}

}  // namespace

int Pipeline::scanRows(const PrimitiveSetup& s, const DrawPlan& p, bool full, int tx0, int ty0, int x0, int y0, int x1, int y1,
                       int rowCount, std::uint64_t* live, std::uint64_t* scanned, StageCounts& c) const {
    const ScissorState& sc = state.scissor;
    const auto column = [tx0](long x) { return int(std::clamp(x - tx0, 0L, 64L)); };
    const std::uint64_t scissorColumns = p.scissor ? bitRange(column(sc.x), column(long(sc.x) + sc.width)) : ~std::uint64_t(0);
    const bool stippleAtScan = p.stipple && !p.stippleLate && !p.stippleStart;
    int survivors = 0;
    for (int row = 0; row < rowCount; ++row) {
        const int y = ty0 + row;
        std::uint64_t m = y >= y0 && y < y1 ? coverageBits(s, full, tx0, x0, x1, y) : 0;
        c.generated += bitCount(m);
        const std::uint64_t inScissor = !p.scissor || (y >= sc.y && long(y) < long(sc.y) + sc.height) ? scissorColumns : 0;
        scanned[row] = m & inScissor;
        if (m && stippleAtScan) m = keep(m, stippleBits(state.stipple.rows[y & 31], tx0), c.rejected[int(Stage::Stipple)]);
        if (m && p.scissor) m = keep(m, inScissor, c.rejected[int(Stage::Scissor)]);
        live[row] = m;
        survivors += bitCount(m);
    }
    return survivors;
}

namespace {

// One row's depth test with the comparison fixed at compile time, so the
// loop has no switch; returns the passing bits of `live`.
template <CompareFunc F>
std::uint64_t depthTestRow(const PrimitiveSetup& s, float* depth, int tx0, int y, int c0, int c1, std::uint64_t live, bool writes) {
    std::uint64_t pass = 0;
    for (int i = c0; i < c1; ++i) {
        if (!(live >> i & 1u)) continue;
        const float z = s.depthAt(tx0 + i, y);
        if (!compare(F, z, depth[i])) continue;
        if (writes) depth[i] = z;
        pass |= std::uint64_t(1) << i;
    }
    return pass;
}

template <CompareFunc F>
void depthTestRowsAs(const PrimitiveSetup& s, Framebuffer& fb, int tx0, int ty0, int x0, int x1, int rowCount, bool writes,
                     std::uint64_t* live, std::int64_t& rejected) {
    for (int row = 0; row < rowCount; ++row) {
        if (!live[row]) continue;
        const int y = ty0 + row;
        const std::uint64_t pass = depthTestRow<F>(s, &fb.depth[fb.index(tx0, y)], tx0, y, x0 - tx0, x1 - tx0, live[row], writes);
        rejected += bitCount(live[row] & ~pass);
        live[row] = pass;
    }
}

}  // namespace

void Pipeline::depthTestRows(const PrimitiveSetup& s, const DrawPlan& p, int tx0, int ty0, int x0, int x1, int rowCount,
                             std::uint64_t* live, StageCounts& c) const {
    std::int64_t& rejected = c.rejected[int(Stage::DepthEarly)];
    const bool w = p.depthWrites;
    switch (state.depth.func) {
        case CompareFunc::Never: return depthTestRowsAs<CompareFunc::Never>(s, fb_, tx0, ty0, x0, x1, rowCount, w, live, rejected);
        case CompareFunc::Less: return depthTestRowsAs<CompareFunc::Less>(s, fb_, tx0, ty0, x0, x1, rowCount, w, live, rejected);
        case CompareFunc::Equal: return depthTestRowsAs<CompareFunc::Equal>(s, fb_, tx0, ty0, x0, x1, rowCount, w, live, rejected);
        case CompareFunc::LessEqual: return depthTestRowsAs<CompareFunc::LessEqual>(s, fb_, tx0, ty0, x0, x1, rowCount, w, live, rejected);
        case CompareFunc::Greater: return depthTestRowsAs<CompareFunc::Greater>(s, fb_, tx0, ty0, x0, x1, rowCount, w, live, rejected);
        case CompareFunc::NotEqual: return depthTestRowsAs<CompareFunc::NotEqual>(s, fb_, tx0, ty0, x0, x1, rowCount, w, live, rejected);
        case CompareFunc::GreaterEqual:
            return depthTestRowsAs<CompareFunc::GreaterEqual>(s, fb_, tx0, ty0, x0, x1, rowCount, w, live, rejected);
        case CompareFunc::Always: return depthTestRowsAs<CompareFunc::Always>(s, fb_, tx0, ty0, x0, x1, rowCount, w, live, rejected);
    }
}

// Coarse tests see per-tile summaries (min/max depth, stencil) as hierarchical
// Z/stencil hardware keeps them; here they are computed exactly on demand.
bool Pipeline::coarseReject(const PrimitiveSetup& s, const DrawPlan& p, int tx0, int ty0, int tx1, int ty1,
                            Stage& stage) const {
    tx1 = std::min(tx1, fb_.width), ty1 = std::min(ty1, fb_.height);
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    bool stencilAllFail = true;
    for (int y = ty0; y < ty1; ++y)
        for (int x = tx0; x < tx1; ++x) {
            const std::size_t idx = fb_.index(x, y);
            lo = std::min(lo, fb_.depth[idx]), hi = std::max(hi, fb_.depth[idx]);
            if (p.coarseStencil && stencilPasses(state.stencil, fb_.stencil[idx])) stencilAllFail = false;
        }
    if (p.coarseBounds && (hi < state.bounds.zmin || lo > state.bounds.zmax)) return stage = Stage::Bounds, true;
    if (p.coarseStencil && stencilAllFail) return stage = Stage::Stencil, true;
    if (!p.coarseDepth) return false;
    const float corners[4] = {s.depthAt(tx0, ty0), s.depthAt(tx1 - 1, ty0), s.depthAt(tx0, ty1 - 1), s.depthAt(tx1 - 1, ty1 - 1)};
    const float zlo = std::clamp(*std::min_element(corners, corners + 4), 0.0f, 1.0f);
    const float zhi = std::clamp(*std::max_element(corners, corners + 4), 0.0f, 1.0f);
    if (rangeFails(state.depth.func, zlo, zhi, lo, hi)) return stage = Stage::DepthEarly, true;
    return false;
}

// Hierarchical culling: each coarse tile whose covered fragments would all
// fail is rejected whole, its quads cleared before any per-pixel work.
void Pipeline::cullCoarseTiles(const PrimitiveSetup& s, const DrawPlan& p, int tx0, int ty0, int y1, int x1,
                               std::uint8_t* masks, StageCounts& c) const {
    const int qw = p.tileW / 2, ct = p.coarseTile;
    for (int cy = ty0; cy < y1; cy += ct)
        for (int cx = tx0; cx < x1; cx += ct) {
            int live = 0;
            const int qy1 = std::min(cy + ct, y1), qx1 = std::min(cx + ct, x1);  // masks beyond are unset
            for (int qy = cy; qy < qy1; qy += 2)
                for (int qx = cx; qx < qx1; qx += 2) live += lanes((masks[((qy - ty0) / 2) * qw + (qx - tx0) / 2]));
            Stage stage;
            if (live == 0 || !coarseReject(s, p, cx, cy, cx + ct, cy + ct, stage)) continue;
            c.rejected[int(stage)] += live;
            ++c.tilesCulled;
            for (int qy = cy; qy < qy1; qy += 2)
                for (int qx = cx; qx < qx1; qx += 2) masks[((qy - ty0) / 2) * qw + (qx - tx0) / 2] = 0;
        }
}

}  // namespace weft::hwsim
