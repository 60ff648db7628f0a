#pragma once
// Image-plane sampling and reconstruction for any technique that traces
// camera rays. The technique supplies a shader (camera sample -> RGBA); this
// decides where samples go and how they become pixels:
//   pattern    a PatternSet spec (pattern_set.hpp): supersampling with the
//              same pattern in every pixel or an interleaved set. Empty keeps
//              the plain default (PlainSamples): the pixel centre at 1 spp,
//              else independent uniform positions per pixel and sample; or,
//              as a technique chooses, the stratified PixelSampler positions
//              of the mesh techniques, or pixel centres at any spp.
//   filter     box (the pixel's own samples) or a wider reconstruction filter:
//              every sample within the filter radius of a pixel centre counts,
//              across pixel boundaries, as a weighted average (Wolberg 6.3.6).
//   adaptive   supersample: Wolberg 6.2.2, corners of a pixel, split in four
//              where a corner differs from their mean by more than the
//              threshold, down to `adaptive_depth` levels; a square is the
//              mean of its corners or of its four quarters (area-weighted),
//              and all samples take the middle of the shutter. stochastic:
//              6.3.5, the pattern's samples first, `adaptive_spp` more where
//              their contrast (Imax - Imin) / (Imax + Imin) exceeds the
//              threshold.
// Plain supersampling visits each row one regular sub-grid at a time, so an
// interleaved set costs the same per sample as one regular grid. Every value
// is a pure function of (seed, pixel, sample index): images are the same at
// any thread count.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/base/run/counters.hpp"
#include "core/image/image.hpp"
#include "core/base/options/params.hpp"
#include "core/base/run/render_context.hpp"
#include "core/sampling/filters.hpp"
#include "core/sampling/pattern_set.hpp"
#include "core/sampling/pixel_sampler.hpp"

namespace weft {

// A shader returns Rgba or RgbaD; a pixel's samples are summed in that
// type (a technique that summed in double keeps doing so).
template <class T>
struct RgbaT {
    T r = 0, g = 0, b = 0, a = 0;
    RgbaT& operator+=(const RgbaT& o) { r += o.r, g += o.g, b += o.b, a += o.a; return *this; }
    RgbaT operator*(T s) const { return {r * s, g * s, b * s, a * s}; }
    RgbaT<float> toFloat() const { return {float(r), float(g), float(b), float(a)}; }
};
using Rgba = RgbaT<float>;
using RgbaD = RgbaT<double>;

// Where a camera ray goes: continuous image position, a time in [0, 1), the
// pixel it belongs to and its index there (for the technique's own random numbers).
struct CameraSample {
    double x = 0, y = 0;
    float time = 0.5f;
    int px = 0, py = 0;
    std::uint32_t index = 0;
};

enum class AdaptiveMode { Off, Supersample, Stochastic };

// Where samples go when no pattern is set (not a parameter: the technique's
// own default). Uniform: the pixel centre at 1 spp, else pixelRandom
// positions and times. Jittered: the pixel centre at 1 spp, else one
// uniform point in each cell of an n x n grid when spp = n^2 (Wolberg
// 6.3.4) and Stratified's positions otherwise, with Stratified's times; the
// volume techniques' default, whose edge error falls faster with spp than
// Uniform's. Stratified: PixelSampler(seed, pixel, k, spp) dimensions 0 and
// 1 and kShutterDim, the mesh techniques' Latin hypercube. Centres: the
// pixel centre at any spp, with Stratified's times.
enum class PlainSamples { Uniform, Jittered, Stratified, Centres };

struct ImagePlaneOptions {
    std::string pattern;
    PlainSamples plain = PlainSamples::Uniform;
    FilterKind filter = FilterKind::Box;
    double filterRadius = 0;
    AdaptiveMode adaptive = AdaptiveMode::Off;
    double threshold = 0.05;
    int depth = 3;
    int extraSpp = 16;
};

// pattern, filter, filter_radius, adaptive, adaptive_threshold, adaptive_depth,
// adaptive_spp; `plain` is the technique's default without a pattern (the
// pattern's doc names it).
std::vector<ParamSpec> imagePlaneParamSpecs(PlainSamples plain = PlainSamples::Uniform);
// A technique's own parameters followed by the image plane's.
std::vector<ParamSpec> withImagePlaneParams(std::vector<ParamSpec> specs, PlainSamples plain = PlainSamples::Uniform);
// Reads and cross-checks them (adaptive modes reconstruct with the box filter).
ImagePlaneOptions readImagePlaneOptions(const ParamSet& p, PlainSamples plain = PlainSamples::Uniform);

class ImagePlane {
public:
    ImagePlane(const ImagePlaneOptions& options, const RenderSettings& settings);

    // The patterns of one pixel, looked up once per pixel.
    struct PixelPatterns {
        const PatternPoint* first = nullptr;  // spp samples, or null: the plain default
        const PatternPoint* extra = nullptr;  // adaptive stochastic's extra samples
    };
    PixelPatterns patternsOf(int px, int py) const;
    // Sample k of pixel (px, py) from the pattern (k < spp) or, for k >= spp,
    // from the extra set of adaptive stochastic sampling.
    CameraSample sample(int px, int py, int k, const PixelPatterns& patterns) const;
    CameraSample sample(int px, int py, int k) const { return sample(px, py, k, patternsOf(px, py)); }

    // Renders the image. makeShader() is called once per row, on the thread
    // that renders it; the shader is callable as Rgba or RgbaD
    // (const CameraSample&) and has flush(Counters&).
    template <class MakeShader>
    Image render(RenderContext& ctx, const char* label, MakeShader makeShader) const;

private:
    template <class RowFn> void forEachRow(const char* label, RowFn rowFn) const;
    bool refineStochastic(const std::vector<Rgba>& values) const;

    template <class Shader> void boxRow(Shader& shade, int y, Image& image) const;
    template <class Shader> Rgba boxPixel(Shader& shade, int px, int py, int& used) const;
    template <class Shader> Rgba adaptivePixel(Shader& shade, const std::vector<Rgba>& corners, int px, int py, int& used) const;
    template <class MakeShader> std::vector<Rgba> cornerGrid(RenderContext& ctx, MakeShader& make) const;
    Image gather(const std::vector<std::vector<float>>& rows) const;

    ImagePlaneOptions opt_;
    RenderSettings settings_;
    ReconstructionFilter filter_;
    std::optional<PatternSet> patterns_, extra_;
    int jitterGrid_ = 0;  // n where plain is Jittered and spp = n^2, else 0
};

}  // namespace weft

#include "core/sampling/image_plane_impl.hpp"
