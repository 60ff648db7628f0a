#pragma once
// Splitting a buffer into n x m interleaved sub-buffers and gathering it
// back (Segovia et al. 2006, sections 3.2-3.4). Pixel (x, y) belongs to
// sub-buffer (x mod n, y mod m) at local position (x / n, y / m); the
// sub-buffers are tiled into a buffer of the original size, so sizes that n
// and m do not divide simply give sub-buffers of different sizes.
//
// One pass moves every texel straight to its place. The two-pass variant
// first splits each p x q block into its n x m sub-blocks (all accesses stay
// inside the block), then translates whole sub-block rectangles to their
// sub-buffers (row copies). p must be a multiple of n and q of m so every
// block starts on a pattern boundary. Both give the same result.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace weft {

class SubBufferLayout {
public:
    SubBufferLayout(int width, int height, int n, int m) : width_(width), height_(height), n_(n), m_(m) {
        x0_ = origins(width, n), y0_ = origins(height, m);
    }
    int width() const { return width_; }
    int height() const { return height_; }
    int n() const { return n_; }
    int m() const { return m_; }
    int count() const { return n_ * m_; }
    // Sub-buffer of a pixel, numbered row by row: (y mod m) * n + (x mod n).
    int index(int x, int y) const { return (y % m_) * n_ + x % n_; }
    // Rectangle of sub-buffer (i, j) in the split buffer.
    int x0(int i) const { return x0_[std::size_t(i)]; }
    int y0(int j) const { return y0_[std::size_t(j)]; }
    int subWidth(int i) const { return x0_[std::size_t(i) + 1] - x0_[std::size_t(i)]; }
    int subHeight(int j) const { return y0_[std::size_t(j) + 1] - y0_[std::size_t(j)]; }
    std::size_t splitOffset(int x, int y) const {
        return std::size_t(y0_[std::size_t(y % m_)] + y / m_) * width_ + std::size_t(x0_[std::size_t(x % n_)] + x / n_);
    }

    // Start of each of k interleaved classes over `size` positions, plus the end.
    static std::vector<int> origins(int size, int k) {
        std::vector<int> o(std::size_t(k) + 1, 0);
        for (int i = 0; i < k; ++i) o[std::size_t(i) + 1] = o[std::size_t(i)] + std::max(0, (size - i + k - 1) / k);
        return o;
    }

private:
    int width_, height_, n_, m_;
    std::vector<int> x0_, y0_;
};

// Keeps a texel as it is; splits may instead convert texels on the way (to
// move only what the next pass reads).
struct KeepTexel {
    template <class T>
    const T& operator()(const T& t) const { return t; }
};

template <class Src, class Dst, class Convert = KeepTexel>
void splitOnePass(const Src& src, Dst& dst, const SubBufferLayout& L, Convert convert = {}) {
    dst.resize(src.size());
    tbb::parallel_for(0, L.height(), [&](int y) {
        for (int x = 0; x < L.width(); ++x) dst[L.splitOffset(x, y)] = convert(src[std::size_t(y) * L.width() + x]);
    });
}

template <class Buffer>
void gatherOnePass(const Buffer& src, Buffer& dst, const SubBufferLayout& L) {
    dst.resize(src.size());
    tbb::parallel_for(0, L.height(), [&](int y) {
        for (int x = 0; x < L.width(); ++x) dst[std::size_t(y) * L.width() + x] = src[L.splitOffset(x, y)];
    });
}

namespace detail {

// Calls fn(bx, by, bw, bh) for every p x q block (clipped at the border), in parallel by block rows.
template <class Fn>
void forEachBlock(const SubBufferLayout& L, int p, int q, Fn fn) {
    const int rows = (L.height() + q - 1) / q;
    tbb::parallel_for(0, rows, [&](int br) {
        const int by = br * q, bh = std::min(q, L.height() - by);
        for (int bx = 0; bx < L.width(); bx += p) fn(bx, by, std::min(p, L.width() - bx), bh);
    });
}

// Pass 1 (block splitting) or its inverse: swizzle inside one block.
template <class Src, class Dst, class Convert>
void swizzleBlock(const Src& src, Dst& dst, const SubBufferLayout& L, int bx, int by, int bw,
                  int bh, bool inverse, Convert convert) {
    const std::vector<int> sx = SubBufferLayout::origins(bw, L.n()), sy = SubBufferLayout::origins(bh, L.m());
    for (int ly = 0; ly < bh; ++ly) {
        const std::size_t toRow = std::size_t(by + sy[std::size_t(ly % L.m())] + ly / L.m()) * L.width();
        const std::size_t fromRow = std::size_t(by + ly) * L.width();
        for (int lx = 0; lx < bw; ++lx) {
            const std::size_t plain = fromRow + std::size_t(bx + lx);
            const std::size_t split = toRow + std::size_t(bx + sx[std::size_t(lx % L.n())] + lx / L.n());
            if (inverse) dst[plain] = convert(src[split]);
            else dst[split] = convert(src[plain]);
        }
    }
}

// Pass 2 (block translation) or its inverse: move the sub-block rectangles.
template <class Buffer>
void translateBlock(const Buffer& src, Buffer& dst, const SubBufferLayout& L, int bx, int by, int bw,
                    int bh, bool inverse) {
    const std::vector<int> sx = SubBufferLayout::origins(bw, L.n()), sy = SubBufferLayout::origins(bh, L.m());
    for (int j = 0; j < L.m(); ++j)
        for (int i = 0; i < L.n(); ++i) {
            const int cw = sx[std::size_t(i) + 1] - sx[std::size_t(i)];
            for (int r = 0; r < sy[std::size_t(j) + 1] - sy[std::size_t(j)]; ++r) {
                const std::size_t blockPos = std::size_t(by + sy[std::size_t(j)] + r) * L.width() + std::size_t(bx + sx[std::size_t(i)]);
                const std::size_t subPos = std::size_t(L.y0(j) + by / L.m() + r) * L.width() + std::size_t(L.x0(i) + bx / L.n());
                if (inverse) std::copy_n(src.begin() + std::ptrdiff_t(subPos), cw, dst.begin() + std::ptrdiff_t(blockPos));
                else std::copy_n(src.begin() + std::ptrdiff_t(blockPos), cw, dst.begin() + std::ptrdiff_t(subPos));
            }
        }
}

}  // namespace detail

// p x q blocks; `scratch` holds the intermediate block-split buffer.
template <class Src, class Dst, class Convert = KeepTexel>
void splitTwoPass(const Src& src, Dst& dst, Dst& scratch, const SubBufferLayout& L, int p,
                  int q, Convert convert = {}) {
    scratch.resize(src.size()), dst.resize(src.size());
    detail::forEachBlock(L, p, q, [&](int bx, int by, int bw, int bh) { detail::swizzleBlock(src, scratch, L, bx, by, bw, bh, false, convert); });
    detail::forEachBlock(L, p, q, [&](int bx, int by, int bw, int bh) { detail::translateBlock(scratch, dst, L, bx, by, bw, bh, false); });
}

template <class Buffer>
void gatherTwoPass(const Buffer& src, Buffer& dst, Buffer& scratch, const SubBufferLayout& L, int p, int q) {
    scratch.resize(src.size()), dst.resize(src.size());
    detail::forEachBlock(L, p, q, [&](int bx, int by, int bw, int bh) { detail::translateBlock(src, scratch, L, bx, by, bw, bh, true); });
    detail::forEachBlock(L, p, q, [&](int bx, int by, int bw, int bh) { detail::swizzleBlock(scratch, dst, L, bx, by, bw, bh, true, KeepTexel{}); });
}

}  // namespace weft
