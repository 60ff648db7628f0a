// Row masks of a scan tile give the answers of the per-pixel tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/base/rng.hpp"
#include "hwsim/tile_masks.hpp"

namespace weft::hwsim {
namespace {

// Triangles with vertices on pixel centres and edges (ties under every fill
// rule) and anywhere else, against PrimitiveSetup::covers pixel by pixel.
TEST(HwsimTileMasks, CoverageRowsMatchThePixelTest) {
    Rng rng(7);
    SpanRows spans;
    int covered = 0;
    for (int t = 0; t < 300; ++t) {
        Vertex v[3];
        for (Vertex& p : v) {
            const float x = rng.uniform() * 80 - 8, y = rng.uniform() * 80 - 8;
            p = t % 3 == 0 ? Vertex{std::floor(x) + 0.5f, std::floor(y) + 0.5f, 0.5f} : t % 3 == 1 ? Vertex{std::floor(x), std::floor(y), 0.5f}
                                                                                                 : Vertex{x, y, 0.5f};
        }
        const FillRule rule = FillRule(t % 4);
        for (const PrimitiveSetup& s : {setupTriangle(v, rule, 64, 64), setupTriangleSpans(v, 64, 64, spans)}) {
            if (s.empty()) continue;
            for (int tileW : {16, 32, 64})
                for (int tx0 = 0; tx0 < 64; tx0 += tileW)
                    for (int y = s.y0; y < s.y1; ++y) {
                        const int x0 = std::max(tx0, s.x0), x1 = std::min(tx0 + tileW, s.x1);
                        const std::uint64_t bits = coverageBits(s, false, tx0, x0, x1, y);
                        for (int x = tx0; x < tx0 + tileW; ++x) {
                            const bool expected = x >= x0 && x < x1 && s.covers(x, y);
                            ASSERT_EQ(bool(bits >> (x - tx0) & 1u), expected) << "triangle " << t << " pixel " << x << ", " << y;
                            covered += expected;
                        }
                    }
        }
    }
    EXPECT_GT(covered, 10000);  // the triangles were not all empty
}

TEST(HwsimTileMasks, StippleBitsRepeatTheRowEvery32Pixels) {
    const std::uint32_t row = 0x8000'0001u | 0x0f00u;
    for (int tx0 : {0, 16, 32, 48, 64, 80})
        for (int i = 0; i < 64; ++i) EXPECT_EQ(stippleBits(row, tx0) >> i & 1u, row >> ((tx0 + i) & 31) & 1u) << tx0 << " " << i;
}

TEST(HwsimTileMasks, StampsHitCountsStampsWithAnySetPixel) {
    Rng rng(3);
    for (int trial = 0; trial < 200; ++trial) {
        std::uint64_t rows[64];
        const int count = 2 * (1 + trial % 32);
        std::uint64_t previous = 0;
        for (int r = 0; r < count; ++r) {
            rows[r] = rng.uniform() < 0.7f ? 0 : (std::uint64_t(1) << int(rng.uniform() * 64)) | (rng.uniform() < 0.5f ? 0 : previous);
            previous = rows[r];
        }
        for (int stampW : {1, 2, 4, 8, 16})
            for (int stampH : {1, 2, 4, 8, 16}) {
                std::int64_t expected = 0;
                for (int sy = 0; sy < count; sy += stampH)
                    for (int sx = 0; sx < 64; sx += stampW) {
                        bool any = false;
                        for (int y = sy; y < std::min(sy + stampH, count); ++y)
                            for (int x = sx; x < sx + stampW; ++x) any |= bool(rows[y] >> x & 1u);
                        expected += any;
                    }
                EXPECT_EQ(stampsHit(rows, count, stampW, stampH), expected) << stampW << "x" << stampH;
            }
    }
    EXPECT_EQ(bitCount(~std::uint64_t(0)), 64);
    EXPECT_EQ(bitRange(3, 64), ~std::uint64_t(7));
}

}  // namespace
}  // namespace weft::hwsim
