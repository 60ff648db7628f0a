// Split then gather is the identity, one-pass and two-pass agree, and every
// sub-buffer holds exactly its interleaved class, for patterns and block
// sizes that do and do not divide the image.
#include <gtest/gtest.h>

#include <numeric>

#include "core/screen/interleave.hpp"

using namespace weft;

namespace {

std::vector<int> ramp(int w, int h) {
    std::vector<int> v(std::size_t(w) * h);
    std::iota(v.begin(), v.end(), 0);
    return v;
}

// Every texel of sub-buffer (i, j) comes from a pixel with x mod n == i, y mod m == j, in raster order.
void expectClassesInPlace(const std::vector<int>& split, const SubBufferLayout& L) {
    for (int j = 0; j < L.m(); ++j)
        for (int i = 0; i < L.n(); ++i)
            for (int ly = 0; ly < L.subHeight(j); ++ly)
                for (int lx = 0; lx < L.subWidth(i); ++lx) {
                    const int v = split[std::size_t(L.y0(j) + ly) * L.width() + std::size_t(L.x0(i) + lx)];
                    ASSERT_EQ(v % L.width(), i + lx * L.n());
                    ASSERT_EQ(v / L.width(), j + ly * L.m());
                }
}

}  // namespace

TEST(Interleave, SubBuffersTileTheImage) {
    const SubBufferLayout L(10, 7, 3, 2);
    EXPECT_EQ(L.subWidth(0), 4);
    EXPECT_EQ(L.subWidth(1), 3);
    EXPECT_EQ(L.subWidth(2), 3);
    EXPECT_EQ(L.subHeight(0), 4);
    EXPECT_EQ(L.subHeight(1), 3);
    EXPECT_EQ(L.x0(2) + L.subWidth(2), 10);
    EXPECT_EQ(L.y0(1) + L.subHeight(1), 7);
    EXPECT_EQ(L.index(4, 3), 1 * 3 + 1);
}

TEST(Interleave, SplitThenGatherIsTheIdentityForAllPatternsAndBlocks) {
    const std::pair<int, int> sizes[] = {{16, 12}, {17, 13}, {5, 3}, {1, 1}, {33, 8}, {7, 29}};
    for (auto [w, h] : sizes)
        for (int n = 1; n <= 5; ++n)
            for (int m = 1; m <= 4; ++m) {
                const SubBufferLayout L(w, h, n, m);
                const std::vector<int> src = ramp(w, h);
                std::vector<int> one, back, scratch;
                splitOnePass(src, one, L);
                expectClassesInPlace(one, L);
                gatherOnePass(one, back, L);
                ASSERT_EQ(back, src) << w << "x" << h << " pattern " << n << "x" << m;
                for (int bp = 1; bp <= 4; ++bp)
                    for (int bq : {1, 2, 5}) {
                        std::vector<int> two, back2;
                        splitTwoPass(src, two, scratch, L, n * bp, m * bq);
                        ASSERT_EQ(two, one) << w << "x" << h << " pattern " << n << "x" << m << " block " << n * bp << "x" << m * bq;
                        gatherTwoPass(two, back2, scratch, L, n * bp, m * bq);
                        ASSERT_EQ(back2, src) << w << "x" << h << " pattern " << n << "x" << m << " block " << n * bp << "x" << m * bq;
                    }
            }
}

TEST(Interleave, PatternLargerThanTheImageLeavesEmptySubBuffers) {
    const SubBufferLayout L(3, 2, 5, 4);
    EXPECT_EQ(L.subWidth(4), 0);
    EXPECT_EQ(L.subHeight(3), 0);
    const std::vector<int> src = ramp(3, 2);
    std::vector<int> split, back, scratch;
    splitTwoPass(src, split, scratch, L, 5, 4);
    gatherTwoPass(split, back, scratch, L, 5, 4);
    EXPECT_EQ(back, src);
}
