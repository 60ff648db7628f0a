#pragma once
// The per-fragment part of Pipeline (templates on the fragment program).
// Included by pipeline.hpp only.

namespace weft::hwsim {

inline void Pipeline::countPrimitive(const PrimitiveSetup& s) {
    ++counts_.clippingInputPrimitives;
    counts_.clippingOutputPrimitives += !(s.zeroArea && profile_.clippingOutputSkipsZeroArea);
}

template <class Program>
void Pipeline::draw(const PrimitiveSetup& s, Program& program, const ProgramTraits& traits) {
    const DrawPlan p = plan(traits);
    countPrimitive(s);
    if (!s.empty()) scanBinned(std::span<const PrimitiveSetup>(&s, 1), program, p);
}

template <class Program>
void Pipeline::drawTriangles(std::span<const std::array<Vertex, 3>> triangles, Program&& program, ProgramTraits traits) {
    const DrawPlan p = plan(traits);  // one state for the whole call, as in GL
    std::vector<SpanRows> spans(profile_.floatSpans ? triangles.size() : 0);  // each triangle keeps its own
    std::vector<PrimitiveSetup> setups;
    setups.reserve(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const Vertex v[3] = {triangles[i][0], triangles[i][1], triangles[i][2]};
        PrimitiveSetup s = profile_.floatSpans ? setupTriangleSpans(v, fb_.width, fb_.height, spans[i])
                                               : setupTriangle(v, profile_.fillRule, fb_.width, fb_.height);
        s.primitive = int(i);
        countPrimitive(s);
        if (!s.empty()) setups.push_back(s);
    }
    if (!setups.empty()) scanBinned(setups, program, p);
}

// Bins are one tile row high and kBinTiles tiles wide, on a global tile grid,
// so every (primitive, tile) pair is scanned once; each bin takes the
// primitives in draw order, and bins run in parallel.
template <class Program>
void Pipeline::scanBinned(std::span<const PrimitiveSetup> setups, Program& program, const DrawPlan& p) {
    int x0 = fb_.width, y0 = fb_.height, x1 = 0, y1 = 0;  // the union of the boxes
    long area = 0;
    for (const PrimitiveSetup& s : setups) {
        x0 = std::min(x0, s.x0), y0 = std::min(y0, s.y0), x1 = std::max(x1, s.x1), y1 = std::max(y1, s.y1);
        area += long(s.x1 - s.x0) * (s.y1 - s.y0);
    }
    constexpr int kBinTiles = 8;
    const int binW = p.tileW * kBinTiles, bx0 = x0 / binW, by0 = y0 / p.tileH;
    const int binCols = (x1 - 1) / binW - bx0 + 1, binRows = (y1 - 1) / p.tileH - by0 + 1;
    tbb::combinable<StageCounts> perThread;
    auto binsBody = [&](const tbb::blocked_range<int>& r) {
        StageCounts& c = perThread.local();
        for (int bin = r.begin(); bin != r.end(); ++bin) {
            const int bxPix = (bx0 + bin % binCols) * binW, ty = (by0 + bin / binCols) * p.tileH;
            for (const PrimitiveSetup& s : setups) {
                if (s.y1 <= ty || s.y0 >= ty + p.tileH || s.x1 <= bxPix || s.x0 >= bxPix + binW) continue;
                if (!s.spans && classifyTile(s.edges, bxPix, ty, bxPix + binW, ty + p.tileH) == TileCoverage::None) continue;
                const int txEnd = std::min(s.x1, bxPix + binW);
                for (int tx = std::max(s.x0, bxPix) / p.tileW * p.tileW; tx < txEnd; tx += p.tileW) scanTile(s, program, p, tx, ty, c);
            }
        }
    };
    const int bins = binCols * binRows;
    if (parallel_ && bins > 1 && area >= 16384) tbb::parallel_for(tbb::blocked_range<int>(0, bins), binsBody);
    else binsBody(tbb::blocked_range<int>(0, bins));
    perThread.combine_each([&](const StageCounts& c) { counts_.add(c); });
}

// One tile: coverage and the rasterizer's tests for every pixel row, then
// the coarse test of the whole tile, then each live quad through the rest.
template <class Program>
void Pipeline::scanTile(const PrimitiveSetup& s, Program& program, const DrawPlan& p, int tx0, int ty0,
                        StageCounts& c) const {
    const int x0 = std::max(tx0, s.x0), y0 = std::max(ty0, s.y0);
    const int x1 = std::min(tx0 + p.tileW, s.x1), y1 = std::min(ty0 + p.tileH, s.y1);
    const TileCoverage coverage = s.spans ? TileCoverage::Partial : classifyTile(s.edges, tx0, ty0, tx0 + p.tileW, ty0 + p.tileH);
    if (coverage == TileCoverage::None) return;
    const int rowCount = (y1 - ty0 + 1) & ~1;  // whole quads
    std::array<std::uint64_t, 64> live, scanned;  // per pixel row; scanned: covered and inside the scissor
    const int liveCount = scanRows(s, p, coverage == TileCoverage::Full, tx0, ty0, x0, y0, x1, y1, rowCount, live.data(), scanned.data(), c);
    if (p.statsAtScan) c.fragmentShaderInvocations += stampsHit(scanned.data(), rowCount, p.stampW, p.stampH) * p.stampW * p.stampH;
    if (liveCount == 0) return;
    if (p.depthFirst) depthTestRows(s, p, tx0, ty0, x0, x1, rowCount, live.data(), c);
    if constexpr (!requires(const FragmentOutput& o) { program.writeOutputs(Fragment{}, o); }) {
        if (p.flat) return shadeFlatTile(s, program, p, tx0, ty0, rowCount, live.data(), c);
    }
    const int qw = p.tileW / 2, quadRows = rowCount / 2, quadCols = (x1 - tx0 + 1) / 2;
    // A quad's live lanes come from the row masks; only coarse culling needs
    // them all in an array first (it clears whole coarse tiles of them).
    const auto quadMask = [&](int qyi, int qxi) {
        return unsigned((live[2 * qyi] >> 2 * qxi & 3u) | (live[2 * qyi + 1] >> 2 * qxi & 3u) << 2);
    };
    std::array<std::uint8_t, 32 * 32> masks;  // tiles are at most 64 x 64
    if (p.coarse) {
        for (int qyi = 0; qyi < quadRows; ++qyi)
            for (int qxi = 0; qxi < quadCols; ++qxi) masks[qyi * qw + qxi] = std::uint8_t(quadMask(qyi, qxi));
        cullCoarseTiles(s, p, tx0, ty0, y1, x1, masks.data(), c);
    }
    // Lock-step blocks cost their slowest lane; only the blocks a quad ran in
    // are set up and summed (a tile often holds a primitive's thin edge only).
    std::array<std::int64_t, 32 * 32> blockMax, blockLanes;  // blocks are at least 2x2 when used: a quad lies in one
    std::array<std::uint16_t, 32 * 32> touched;
    std::array<std::uint64_t, 32 * 32 / 64> isTouched;
    int touchedCount = 0;
    const bool lockStep = p.blockW * p.blockH > 1;
    if (lockStep) std::fill_n(isTouched.begin(), ((p.tileW / p.blockW) * (p.tileH / p.blockH) + 63) / 64, 0);
    const int blockShiftW = std::countr_zero(unsigned(p.blockW)), blockShiftH = std::countr_zero(unsigned(p.blockH));
    std::array<std::uint64_t, 64> ran;  // lanes whose program ran, per pixel row (statistics counted where programs run)
    if (!p.statsAtScan) std::fill_n(ran.begin(), rowCount, 0);
    for (int qyi = 0; qyi < quadRows; ++qyi) {
        std::uint64_t quads = live[2 * qyi] | live[2 * qyi + 1];
        quads = (quads | quads >> 1) & 0x5555555555555555ull;  // bit 2 qxi: the quad had live lanes before coarse culling
        for (; quads; quads &= quads - 1) {
            const int qxi = std::countr_zero(quads) / 2, qx = tx0 + 2 * qxi, qy = ty0 + 2 * qyi;
            const unsigned m = p.coarse ? masks[qyi * qw + qxi] : quadMask(qyi, qxi);
            if (!m) continue;
            unsigned lanesRan;
            if (p.simple) lanesRan = shadePixels(s, program, p, qx, qy, m, c);
            else {
                const int b = ((2 * qyi) >> blockShiftH) * (p.tileW >> blockShiftW) + ((2 * qxi) >> blockShiftW);
                if (lockStep && !(isTouched[b >> 6] >> (b & 63) & 1u)) {
                    isTouched[b >> 6] |= std::uint64_t(1) << (b & 63);
                    touched[touchedCount++] = std::uint16_t(b), blockMax[b] = 0, blockLanes[b] = 0;
                }
                std::int64_t* const blockCost = lockStep ? &blockMax[b] : nullptr;
                lanesRan = p.depthFirst ? shadeTestedQuad(s, program, p, qx, qy, m, c, blockCost, &blockLanes[b])
                                        : shadeQuad(s, program, p, qx, qy, m, c, blockCost, &blockLanes[b]);
            }
            if (!p.statsAtScan) ran[2 * qyi] |= std::uint64_t(lanesRan & 3u) << 2 * qxi, ran[2 * qyi + 1] |= std::uint64_t(lanesRan >> 2 & 3u) << 2 * qxi;
        }
    }
    if (!p.statsAtScan) c.fragmentShaderInvocations += stampsHit(ran.data(), rowCount, p.stampW, p.stampH) * p.stampW * p.stampH;
    for (int i = 0; i < touchedCount; ++i) {
        const int b = touched[i];
        c.cost += blockMax[b] * (p.wholeBlock && blockLanes[b] ? p.blockW * p.blockH : blockLanes[b]);
    }
}

// What scanTile's quad loop and shadeTestedQuad add up for a depth-tested
// tile, from the row masks: every quad with a live lane runs (all four lanes
// where shading is by quads), each lock-step block with a running quad costs
// the program's cost per lane (all its lanes where whole blocks run), and
// each live lane passes and is written.
template <class Program>
void Pipeline::shadeFlatTile(const PrimitiveSetup& s, Program& program, const DrawPlan& p, int tx0, int ty0, int rowCount,
                             const std::uint64_t* live, StageCounts& c) const {
    constexpr std::uint64_t kQuadColumns = 0x5555555555555555ull;  // bit 2 qxi: the quad's left column
    std::int64_t pixels = 0, quads = 0;
    for (int row = 0; row < rowCount; row += 2) {
        const std::uint64_t both = live[row] | live[row + 1];
        pixels += bitCount(live[row]) + bitCount(live[row + 1]);
        quads += bitCount((both | both >> 1) & kQuadColumns);
    }
    if (!p.statsAtScan) c.fragmentShaderInvocations += stampsHit(live, rowCount, p.stampW, p.stampH) * p.stampW * p.stampH;
    if (pixels == 0) return;
    int row0 = 0;
    while (!live[row0]) ++row0;
    const int x = tx0 + std::countr_zero(live[row0]), y = ty0 + row0;
    FragmentOutput o;
    program(Fragment{x, y, s.depthAt(x, y), false, s.primitive}, o);
    const std::int64_t ran = p.quad ? 4 * quads : pixels;
    c.invocations += ran, c.helpers += ran - pixels;
    const bool wholeBlocks = p.wholeBlock && p.blockW * p.blockH > 1;  // blocks holding a live lane, counted as stamps are
    c.cost += o.cost * (wholeBlocks ? stampsHit(live, rowCount, p.blockW, p.blockH) * p.blockW * p.blockH : ran);
    c.samplesPassed += pixels;
    if (p.colorWrites || p.depthWrites) c.pixelsWritten += pixels;
    if (!p.colorWrites) return;
    for (int row = 0; row < rowCount; ++row)
        for (std::uint64_t bits = live[row]; bits; bits &= bits - 1)
            writeColor(fb_.index(tx0 + std::countr_zero(bits), ty0 + row), o.color, p);
}

// The short path (DrawPlan::simple): each live pixel through an optional
// early depth test, the program and the write.
template <class Program>
unsigned Pipeline::shadePixels(const PrimitiveSetup& s, Program& program, const DrawPlan& p, int qx, int qy, unsigned mask,
                               StageCounts& c) const {
    unsigned ran = 0;
    for (int lane = 0; lane < 4; ++lane) {
        if (!(mask >> lane & 1u)) continue;
        const int x = qx + (lane & 1), y = qy + (lane >> 1);
        const std::size_t idx = fb_.index(x, y);
        const float z = s.depthAt(x, y);
        if (p.depth) {
            if (!compare(state.depth.func, z, fb_.depth[idx])) { ++c.rejected[int(Stage::DepthEarly)]; continue; }
            if (p.depthWrites) fb_.depth[idx] = z;
        }
        FragmentOutput o;
        program(Fragment{x, y, z, false, s.primitive}, o);
        ++c.invocations;
        ran |= 1u << lane;
        c.cost += o.cost;
        if (o.discard) { ++c.discarded; continue; }
        ++c.samplesPassed;
        if (p.colorWrites) writeColor(idx, o.color, p);
        if constexpr (requires { program.writeOutputs(Fragment{}, o); }) program.writeOutputs(Fragment{x, y, z, false, s.primitive}, o);
        c.pixelsWritten += p.colorWrites || p.depthWrites;
    }
    return ran;
}

template <class Program>
unsigned Pipeline::shadeTestedQuad(const PrimitiveSetup& s, Program& program, const DrawPlan& p, int qx, int qy, unsigned mask,
                                   StageCounts& c, std::int64_t* blockMax, std::int64_t* blockLanes) const {
    const unsigned shaded = p.quad ? 0xFu : mask;
    const int ran = lanes(shaded);
    c.invocations += ran, c.helpers += ran - lanes(mask);
    FragmentOutput out[4];
    for (int lane = 0; lane < 4; ++lane) {
        if (!(shaded >> lane & 1u)) continue;
        const int x = qx + (lane & 1), y = qy + (lane >> 1);
        const bool inside = x < fb_.width && y < fb_.height;
        if (inside) program(Fragment{x, y, s.depthAt(x, y), !(mask >> lane & 1u), s.primitive}, out[lane]);
        if (!blockMax) c.cost += out[lane].cost;
        else *blockMax = std::max<std::int64_t>(*blockMax, inside ? out[lane].cost : 0);
    }
    if (blockMax) *blockLanes += ran;
    for (int lane = 0; lane < 4; ++lane) {
        if (!(mask >> lane & 1u)) continue;
        const FragmentOutput& o = out[lane];
        if (o.discard) { ++c.discarded; continue; }
        const int x = qx + (lane & 1), y = qy + (lane >> 1);
        ++c.samplesPassed;
        if (p.colorWrites) writeColor(fb_.index(x, y), o.color, p);
        if constexpr (requires { program.writeOutputs(Fragment{}, o); }) program.writeOutputs(Fragment{x, y, s.depthAt(x, y), false, s.primitive}, o);
        c.pixelsWritten += p.colorWrites || p.depthWrites;
    }
    return mask;  // helpers ran too, but for no fragment
}

// One 2x2 quad whose covered lanes passed the rasterizer's tests (mask).
template <class Program>
unsigned Pipeline::shadeQuad(const PrimitiveSetup& s, Program& program, const DrawPlan& p, int qx, int qy, unsigned mask,
                             StageCounts& c, std::int64_t* blockMax, std::int64_t* blockLanes) const {
    Pending pending[4];
    float z[4];
    bool noBoundsFailure = true;
    for (int lane = 0; lane < 4; ++lane) {
        if (!(mask >> lane & 1u)) continue;
        const int x = qx + (lane & 1), y = qy + (lane >> 1);
        const std::size_t idx = fb_.index(x, y);
        z[lane] = s.depthAt(x, y);
        Stage fail = Stage::Count;
        if (p.boundsEarly && !inBounds(idx)) fail = Stage::Bounds;
        else if (p.zsEarly) fail = stencilDepth(idx, z[lane], p, true, p.deferWrites ? &pending[lane] : nullptr);
        if (fail != Stage::Count) ++c.rejected[int(fail)], mask &= ~(1u << lane), noBoundsFailure &= fail != Stage::Bounds;
        else if (p.countEarly) ++c.samplesPassed;
    }
    unsigned killed = 0;  // stippled by a kill at the program's start: the program runs, the fragment dies
    if (p.stippleStart)
        for (int lane = 0; lane < 4; ++lane)
            if ((mask >> lane & 1u) && !stippleKeeps(qx + (lane & 1), qy + (lane >> 1), p.stippleMirrored))
                ++c.rejected[int(Stage::Stipple)], mask &= ~(1u << lane), killed |= 1u << lane;
    if (!mask) {
        if (p.emptyQuadsRun && noBoundsFailure && !killed) {  // the program runs (past a stipple kill), results dropped
            unsigned run = 0xFu;
            for (int lane = 0; lane < 4 && p.stippleStart; ++lane)
                if (!stippleKeeps(qx + (lane & 1), qy + (lane >> 1), p.stippleMirrored)) run &= ~(1u << lane);
            c.invocations += lanes(run);
            return 0;  // for no fragment: softpipe's statistic counts none
        }
        if (killed) c.invocations += p.quad ? 4 : lanes(killed), c.helpers += p.quad ? 4 : lanes(killed);
        return killed;
    }
    const unsigned ran = mask | killed;  // a kill at the program's start comes after the program started
    FragmentOutput out[4];
    const unsigned shaded = p.quad ? 0xFu : mask | killed;
    for (int lane = 0; lane < 4; ++lane) {
        if (!(shaded >> lane & 1u)) continue;
        const int x = qx + (lane & 1), y = qy + (lane >> 1);
        const bool helper = !(mask >> lane & 1u);
        ++c.invocations;
        c.helpers += helper;
        const bool inside = x < fb_.width && y < fb_.height;
        if (inside) program(Fragment{x, y, helper ? s.depthAt(x, y) : z[lane], helper, s.primitive}, out[lane]);
        if (!blockMax) c.cost += out[lane].cost;
        else *blockMax = std::max<std::int64_t>(*blockMax, inside ? out[lane].cost : 0), ++*blockLanes;
    }
    for (int lane = 0; lane < 4; ++lane) {
        if (!(mask >> lane & 1u)) continue;
        const int x = qx + (lane & 1), y = qy + (lane >> 1);
        const std::size_t idx = fb_.index(x, y);
        const FragmentOutput& o = out[lane];
        if (o.discard) { ++c.discarded; continue; }
        if (p.stippleLate && !stippleKeeps(x, y, p.stippleMirrored)) { ++c.rejected[int(Stage::Stipple)]; continue; }
        if (p.bounds && !p.boundsEarly && !inBounds(idx)) { ++c.rejected[int(Stage::Bounds)]; continue; }
        const float zf = p.writesDepth ? (o.depth >= 0.0f ? std::min(o.depth, 1.0f) : 0.0f) : z[lane];  // NaN -> 0
        if (p.zsLate) {
            const Stage fail = stencilDepth(idx, zf, p, false, nullptr);
            if (fail != Stage::Count) { ++c.rejected[int(fail)]; continue; }
        } else if (p.deferWrites) {
            applyPending(idx, pending[lane]);
        }
        if (!p.countEarly) ++c.samplesPassed;
        if (p.colorWrites) writeColor(idx, o.color, p);
        if constexpr (requires { program.writeOutputs(Fragment{}, o); }) program.writeOutputs(Fragment{x, y, zf, false, s.primitive}, o);
        c.pixelsWritten += p.colorWrites || p.depthWrites;
    }
    return ran;
}

inline Stage Pipeline::stencilDepth(std::size_t idx, float z, const DrawPlan& p, bool early, Pending* pending) const {
    const StencilState& st = state.stencil;
    std::uint8_t& stored = fb_.stencil[idx];
    auto stencilUpdate = [&](StencilOp op, Pending* into) {
        if (!p.stencil) return;
        const std::uint8_t v = maskedStencilWrite(stored, applyStencilOp(op, stored, st.ref), st.writeMask);
        if (into) into->stencil = true, into->stencilValue = v;
        else stored = v;
    };
    if (p.stencil && !stencilPasses(st, stored)) {
        stencilUpdate(st.sfail, nullptr);
        return Stage::Stencil;
    }
    if (p.depth && !compare(state.depth.func, z, fb_.depth[idx])) {
        stencilUpdate(st.dpfail, nullptr);
        return early ? Stage::DepthEarly : Stage::DepthLate;
    }
    stencilUpdate(st.dppass, pending);
    if (p.depthWrites) {
        if (pending) pending->depth = true, pending->depthValue = z;
        else fb_.depth[idx] = z;
    }
    return Stage::Count;
}

inline void Pipeline::applyPending(std::size_t idx, const Pending& pending) const {
    if (pending.stencil) fb_.stencil[idx] = pending.stencilValue;
    if (pending.depth) fb_.depth[idx] = pending.depthValue;
}

namespace detail {

inline float factor(BlendFactor f, const std::array<float, 4>& src, const std::array<float, 4>& dst) {
    switch (f) {
        case BlendFactor::Zero: return 0;
        case BlendFactor::One: return 1;
        case BlendFactor::SrcAlpha: return src[3];
        case BlendFactor::OneMinusSrcAlpha: return 1 - src[3];
        case BlendFactor::DstAlpha: return dst[3];
        case BlendFactor::OneMinusDstAlpha: return 1 - dst[3];
    }
    return 1;
}

}  // namespace detail

inline void Pipeline::writeColor(std::size_t idx, const std::array<float, 4>& src, const DrawPlan& p) const {
    float* dst = fb_.colorAt(idx);
    const int channels = fb_.channels;
    if (p.colorReplace) {
        for (int ch = 0; ch < channels; ++ch) dst[ch] = src[std::size_t(ch)];
        return;
    }
    if (p.colorAdd) {
        for (int ch = 0; ch < channels; ++ch) dst[ch] += src[std::size_t(ch)];
        return;
    }
    const std::array<float, 4> stored = fb_.texel(idx);  // what the blend factors read (DST_ALPHA of a target without alpha is 1)
    const BlendState& b = state.blend;
    const float fs = b.enabled ? detail::factor(b.src, src, stored) : 1, fd = b.enabled ? detail::factor(b.dst, src, stored) : 0;
    for (int ch = 0; ch < channels; ++ch)
        if (state.colorMask[std::size_t(ch)]) dst[ch] = b.enabled ? src[std::size_t(ch)] * fs + dst[ch] * fd : src[std::size_t(ch)];
}

}  // namespace weft::hwsim
