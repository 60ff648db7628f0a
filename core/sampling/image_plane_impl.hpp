#pragma once
// Template bodies of ImagePlane (included by image_plane.hpp only).
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>

#include "core/base/run/progress.hpp"
#include "core/base/rng.hpp"

namespace weft {

inline const Counter kImageSamples{"image.samples", "point evaluations of the image function"};

// The one pixel loop of weft: every row of the settings' row band (all
// rows unless a tile is being rendered) in parallel, progress per row.
// Each pixel's result depends only on its own coordinates, so images are
// identical for any thread count.
template <class RowFn>
void ImagePlane::forEachRow(const char* label, RowFn rowFn) const {
    const RenderSettings& s = settings_;
    const int end = s.rowEnd < 0 ? s.height : std::min(s.rowEnd, s.height);
    const int begin = std::clamp(s.rowBegin, 0, end);
    Progress progress(label, end - begin, s.monitor);
    tbb::parallel_for(tbb::blocked_range<int>(begin, end, 1), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) {
            rowFn(y);
            progress.advance();
        }
    });
    progress.finish();
}

// The sample type a shader returns (Rgba or RgbaD).
template <class Shader>
using ShaderValue = std::decay_t<std::invoke_result_t<Shader&, const CameraSample&>>;

inline CameraSample ImagePlane::sample(int px, int py, int k, const PixelPatterns& patterns) const {
    CameraSample s;
    s.px = px, s.py = py, s.index = std::uint32_t(k);
    const bool first = k < settings_.spp;
    if (const PatternPoint* set = first ? patterns.first : patterns.extra) {
        const PatternPoint& p = set[first ? k : k - settings_.spp];
        s.x = px + double(p.x), s.y = py + double(p.y), s.time = p.t;
    } else if (opt_.plain == PlainSamples::Jittered && first && settings_.spp > 1) {
        const PixelSampler sampler(settings_.seed, px, py, std::uint32_t(k), std::uint32_t(settings_.spp));
        if (const int n = jitterGrid_) {
            s.x = px + (k % n + double(pixelRandom(settings_.seed, px, py, k, 1))) / n;
            s.y = py + (k / n + double(pixelRandom(settings_.seed, px, py, k, 2))) / n;
        } else {
            s.x = px + double(sampler.get(0)), s.y = py + double(sampler.get(1));
        }
        s.time = sampler.get(kShutterDim);
    } else if (opt_.plain == PlainSamples::Stratified || opt_.plain == PlainSamples::Centres) {
        const PixelSampler sampler(settings_.seed, px, py, std::uint32_t(k), std::uint32_t(settings_.spp));
        const bool centre = opt_.plain == PlainSamples::Centres;
        s.x = px + (centre ? 0.5 : double(sampler.get(0))), s.y = py + (centre ? 0.5 : double(sampler.get(1)));
        s.time = sampler.get(kShutterDim);
    } else if (settings_.spp == 1 && k == 0) {
        s.x = px + 0.5, s.y = py + 0.5, s.time = 0.5f;
    } else {
        s.x = px + double(pixelRandom(settings_.seed, px, py, k, 1));
        s.y = py + double(pixelRandom(settings_.seed, px, py, k, 2));
        s.time = pixelRandom(settings_.seed, px, py, k, 3);
    }
    return s;
}

template <class Shader>
Rgba ImagePlane::boxPixel(Shader& shade, int px, int py, int& used) const {
    using V = ShaderValue<Shader>;
    const int spp = settings_.spp;
    V sum;
    std::vector<Rgba> values;
    const bool stochastic = opt_.adaptive == AdaptiveMode::Stochastic;
    const PixelPatterns patterns = patternsOf(px, py);
    for (int k = 0; k < spp; ++k) {
        const V v = shade(sample(px, py, k, patterns));
        sum += v;
        if (stochastic) values.push_back(v.toFloat());
    }
    used = spp;
    if (stochastic && refineStochastic(values)) {
        for (int k = spp; k < spp + opt_.extraSpp; ++k) sum += shade(sample(px, py, k, patterns));
        used += opt_.extraSpp;
    }
    const auto n = decltype(V::r)(used);
    return V{sum.r / n, sum.g / n, sum.b / n, sum.a / n}.toFloat();
}

// Wolberg 6.2.2: a square is the mean of its corners unless one corner
// differs from that mean by more than the threshold; then it is the mean of
// its four quarters. Points on the lattice of the finest level are shaded
// once and shared between neighbouring squares.
template <class Shader>
Rgba ImagePlane::adaptivePixel(Shader& shade, const std::vector<Rgba>& corners, int px, int py, int& used) const {
    const int L = 1 << opt_.depth;
    const int W1 = settings_.width + 1;
    // Lattice values of this pixel, reused across pixels of the thread.
    thread_local std::vector<Rgba> cache;
    thread_local std::vector<char> known;
    cache.resize(std::size_t(L + 1) * (L + 1));
    known.assign(cache.size(), 0);
    used = 4;
    auto value = [&](int i, int j) -> Rgba {
        if ((i == 0 || i == L) && (j == 0 || j == L)) return corners[std::size_t(py + j / L) * W1 + px + i / L];
        const std::size_t key = std::size_t(j) * (L + 1) + i;
        if (known[key]) return cache[key];
        CameraSample s;
        s.x = px + double(i) / L, s.y = py + double(j) / L, s.px = px, s.py = py, s.index = std::uint32_t(used++);
        known[key] = 1;
        return cache[key] = shade(s).toFloat();
    };
    auto differs = [&](const Rgba& c, const Rgba& m) {
        const float t = float(opt_.threshold);
        return std::abs(c.r - m.r) > t || std::abs(c.g - m.g) > t || std::abs(c.b - m.b) > t || std::abs(c.a - m.a) > t;
    };
    auto quad = [&](auto& self, int i, int j, int size) -> Rgba {
        const Rgba c[4] = {value(i, j), value(i + size, j), value(i, j + size), value(i + size, j + size)};
        Rgba mean;
        for (const Rgba& v : c) mean += v * 0.25f;
        if (size == 1 || !(differs(c[0], mean) || differs(c[1], mean) || differs(c[2], mean) || differs(c[3], mean)))
            return mean;
        const int h = size / 2;
        Rgba out;
        out += self(self, i, j, h) * 0.25f, out += self(self, i + h, j, h) * 0.25f;
        out += self(self, i, j + h, h) * 0.25f, out += self(self, i + h, j + h, h) * 0.25f;
        return out;
    };
    return quad(quad, 0, 0, L);
}

template <class MakeShader>
std::vector<Rgba> ImagePlane::cornerGrid(RenderContext& ctx, MakeShader& make) const {
    const int W1 = settings_.width + 1, H1 = settings_.height + 1;
    std::vector<Rgba> corners(std::size_t(W1) * H1);
    tbb::parallel_for(0, H1, [&](int y) {
        auto shade = make();
        for (int x = 0; x < W1; ++x) {
            CameraSample s;
            s.x = x, s.y = y, s.px = x, s.py = y, s.index = 1u << 30;
            corners[std::size_t(y) * W1 + x] = shade(s).toFloat();
        }
        shade.flush(ctx.counters);
        ctx.counters.add(kImageSamples, W1);
    });
    return corners;
}

// Plain supersampling of one row, one regular sub-grid at a time (Keller &
// Heidrich): sample k of the pixels x = a, a + n, a + 2n... (n the tile
// width) all sit at the same offset, so consecutive shader calls see a
// regular grid and stay coherent. Each pixel still sums its own samples in
// index order: the same image as pixel-by-pixel order.
template <class Shader>
void ImagePlane::boxRow(Shader& shade, int y, Image& image) const {
    using V = ShaderValue<Shader>;
    const int W = settings_.width, spp = settings_.spp;
    thread_local std::vector<V> sum;
    thread_local std::vector<PixelPatterns> patterns;
    sum.assign(W, V{});
    patterns.resize(W);
    for (int x = 0; x < W; ++x) patterns[x] = patternsOf(x, y);
    const int n = patterns_ ? patterns_->tileWidth() : 1;
    for (int k = 0; k < spp; ++k) {
        throwIfInterrupted(settings_.monitor);  // a row of many samples takes long: each pass over it polls
        for (int a = 0; a < n; ++a)
            for (int x = a; x < W; x += n) sum[x] += shade(sample(x, y, k, patterns[x]));
    }
    for (int x = 0; x < W; ++x) {
        float* px = image.pixel(x, y);
        const auto n = decltype(V::r)(spp);
        px[0] = float(sum[x].r / n), px[1] = float(sum[x].g / n), px[2] = float(sum[x].b / n), px[3] = float(sum[x].a / n);
    }
}

template <class MakeShader>
Image ImagePlane::render(RenderContext& ctx, const char* label, MakeShader makeShader) const {
    const RenderSettings& s = settings_;
    const bool adaptive = opt_.adaptive != AdaptiveMode::Off;
    const bool wide = !adaptive && !(filter_.kind() == FilterKind::Box && filter_.radius() == 0.5);
    Image image = Image::rgba(s.width, s.height);
    const int countChannel = adaptive ? image.addChannel("sampleCount") : -1;
    std::vector<Rgba> corners;
    if (opt_.adaptive == AdaptiveMode::Supersample) corners = cornerGrid(ctx, makeShader);
    std::vector<std::vector<float>> rows(wide ? s.height : 0);
    forEachRow(label, [&](int y) {
        auto shade = makeShader();
        std::int64_t evaluations = 0;
        if (!adaptive && !wide) {
            boxRow(shade, y, image);
            shade.flush(ctx.counters);
            ctx.counters.add(kImageSamples, std::int64_t(s.width) * s.spp);
            return;
        }
        for (int x = 0; x < s.width; ++x) {
            throwIfInterrupted(s.monitor);
            if (wide) {
                const PixelPatterns patterns = patternsOf(x, y);
                for (int k = 0; k < s.spp; ++k) {
                    const CameraSample cs = sample(x, y, k, patterns);
                    const Rgba v = shade(cs).toFloat();
                    rows[y].insert(rows[y].end(), {float(cs.x), float(cs.y), v.r, v.g, v.b, v.a});
                }
                evaluations += s.spp;
                continue;
            }
            int used = 0;
            const Rgba v = opt_.adaptive == AdaptiveMode::Supersample ? adaptivePixel(shade, corners, x, y, used)
                                                                       : boxPixel(shade, x, y, used);
            float* px = image.pixel(x, y);
            px[0] = v.r, px[1] = v.g, px[2] = v.b, px[3] = v.a;
            if (countChannel >= 0) px[countChannel] = float(used);
            evaluations += opt_.adaptive == AdaptiveMode::Supersample ? used - 4 : used;
        }
        shade.flush(ctx.counters);
        ctx.counters.add(kImageSamples, evaluations);
    });
    return wide ? gather(rows) : image;
}

}  // namespace weft
