#pragma once
// Pixel rows of one scan tile as bit masks (bit i: pixel tx0 + i of the
// row; tiles are at most 64 wide): coverage, stipple and scissor become a
// few word operations per row instead of tests per pixel, with the same
// answers as PrimitiveSetup::covers.
#include <cstdint>

#include "hwsim/raster.hpp"

namespace weft::hwsim {

// Set bits; SWAR, as the baseline x86-64 target has no popcount instruction.
inline int bitCount(std::uint64_t v) {
    v = v - ((v >> 1) & 0x5555555555555555ull);
    v = (v & 0x3333333333333333ull) + ((v >> 2) & 0x3333333333333333ull);
    v = (v + (v >> 4)) & 0x0f0f0f0f0f0f0f0full;
    return int((v * 0x0101010101010101ull) >> 56);
}

// Bits [lo, hi) of a row, 0 <= lo, hi <= 64.
inline std::uint64_t bitRange(int lo, int hi) {
    if (lo >= hi) return 0;
    const std::uint64_t upTo = hi >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << hi) - 1;
    return upTo & ~((std::uint64_t(1) << lo) - 1);
}

// Pixels tx0 .. tx0 + 63 of a stipple row (the 32-bit pattern repeats).
inline std::uint64_t stippleBits(std::uint32_t row, int tx0) {
    const std::uint64_t both = std::uint64_t(row) | std::uint64_t(row) << 32;
    const int s = tx0 & 31;
    return s == 0 ? both : (both >> s) | (both << (64 - s));
}

// Covered centres of row y in columns [x0, x1) of the tile starting at tx0.
// Edge functions step exactly (integers) from the row's first centre.
inline std::uint64_t coverageBits(const PrimitiveSetup& s, bool full, int tx0, int x0, int x1, int y) {
    if (x0 >= x1) return 0;
    if (s.spans) {
        const std::size_t row = std::size_t(y - s.spans->y0);
        if (row >= s.spans->left.size()) return 0;
        const int lo = s.spans->left[row] > x0 ? s.spans->left[row] : x0, hi = s.spans->right[row] < x1 ? s.spans->right[row] : x1;
        return bitRange(lo - tx0, hi - tx0);
    }
    const EdgeSet& e = s.edges;
    if (full || e.count == 0) return bitRange(x0 - tx0, x1 - tx0);
    const std::int64_t px = std::int64_t(x0) * kSubpixel + kSubpixel / 2, py = std::int64_t(y) * kSubpixel + kSubpixel / 2;
    std::int64_t value[4], step[4], least[4];  // inside: value >= least (0 on an owning edge, else 1)
    for (int i = 0; i < 4; ++i) {
        const bool used = i < e.count;
        value[i] = used ? e.a[i] * px + e.b[i] * py + e.c[i] : 0;
        step[i] = used ? e.a[i] * kSubpixel : 0;
        least[i] = used && !e.owns[i] ? 1 : 0;
    }
    std::uint64_t bits = 0;
    for (int x = x0; x < x1; ++x) {
        const bool in = value[0] >= least[0] && value[1] >= least[1] && value[2] >= least[2] && value[3] >= least[3];
        bits |= std::uint64_t(in) << (x - tx0);
        for (int i = 0; i < 4; ++i) value[i] += step[i];
    }
    return bits;
}

// Stamps of stampW x stampH pixels (powers of two, stamps aligned to the
// tile) holding any set bit of rows[0 .. count).
inline std::int64_t stampsHit(const std::uint64_t* rows, int count, int stampW, int stampH) {
    std::uint64_t firstOfStamp = 0;  // the first column of every stamp
    for (int x = 0; x < 64; x += stampW) firstOfStamp |= std::uint64_t(1) << x;
    std::int64_t hit = 0;
    for (int y = 0; y < count; y += stampH) {
        std::uint64_t any = 0;
        for (int r = y; r < y + stampH && r < count; ++r) any |= rows[r];
        for (int shift = 1; shift < stampW; shift <<= 1) any |= any >> shift;  // a stamp's bits fold into its first column
        hit += bitCount(any & firstOfStamp);
    }
    return hit;
}

}  // namespace weft::hwsim
