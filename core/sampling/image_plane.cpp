#include "core/sampling/image_plane.hpp"

#include <cmath>
#include <string>

#include "core/base/error.hpp"
#include "core/base/rng.hpp"

namespace weft {

namespace {

const char* plainSamplesDoc(PlainSamples plain) {
    switch (plain) {
        case PlainSamples::Jittered:
            return "pixel centre at 1 spp, else a jittered grid in each pixel (a Latin hypercube when spp is not a square)";
        case PlainSamples::Stratified: return "a Latin hypercube in each pixel";
        case PlainSamples::Centres: return "pixel centres";
        case PlainSamples::Uniform: break;
    }
    return "pixel centre at 1 spp, else uniform random";
}

// n where spp = n^2 (n > 1), else 0.
int squareRootOf(int spp) {
    const int n = int(std::lround(std::sqrt(double(spp))));
    return n > 1 && n * n == spp ? n : 0;
}

}  // namespace

constexpr double kMinFilterRadius = 0.01;

std::vector<ParamSpec> imagePlaneParamSpecs(PlainSamples plain) {
    return {
        stringParam("pattern", "", std::string("image-plane sample positions: a pattern spec (weft pattern --list), e.g. "
                                               "interleaved:4x4,basis=lp; empty: ") + plainSamplesDoc(plain),
                    [](const std::string& v) { if (!v.empty()) validatePatternSpec(v); }),
        enumParam("filter", "box", {"box", "tent", "gaussian", "mitchell", "bspline", "raised_cosine"},
                  "reconstruction filter; wider than box, samples count across pixel boundaries (weighted average)"),
        floatParam("filter_radius", 0, 0, 8, "filter radius in pixels, 0 or at least 0.01 (0: the filter's customary radius)"),
        enumParam("adaptive", "off", {"off", "supersample", "stochastic"},
                  "supersample: split pixel corners that differ (Wolberg 6.2.2); stochastic: add adaptive_spp "
                  "samples where the pattern's samples differ in contrast (6.3.5)"),
        floatParam("adaptive_threshold", 0.05, 0, 10,
                   "supersample: largest corner difference from their mean; stochastic: largest contrast"),
        intParam("adaptive_depth", 3, 1, 5, "supersample: most subdivision levels (2^depth x 2^depth cells)"),
        intParam("adaptive_spp", 16, 1, 4096, "stochastic: samples added to a pixel that needs them"),
    };
}

std::vector<ParamSpec> withImagePlaneParams(std::vector<ParamSpec> specs, PlainSamples plain) {
    for (ParamSpec& spec : imagePlaneParamSpecs(plain)) specs.push_back(std::move(spec));
    return specs;
}

ImagePlaneOptions readImagePlaneOptions(const ParamSet& p, PlainSamples plain) {
    ImagePlaneOptions o;
    o.plain = plain;
    o.pattern = p.getString("pattern");
    o.filter = ReconstructionFilter::kindFromName(p.getString("filter"));
    o.filterRadius = p.getFloat("filter_radius");
    // A filter a hair wide weighs its samples 1 / radius: 1e-300 overflowed to Inf and every pixel to NaN.
    if (o.filterRadius > 0 && o.filterRadius < kMinFilterRadius)
        throw Error("filter_radius " + formatNumber(o.filterRadius) + " is narrower than 0.01 pixels (no sample would fall in it); "
                    "give 0 for the filter's customary radius, or a radius in [0.01, 8]");
    const std::string a = p.getString("adaptive");
    o.adaptive = a == "supersample" ? AdaptiveMode::Supersample : a == "stochastic" ? AdaptiveMode::Stochastic : AdaptiveMode::Off;
    o.threshold = p.getFloat("adaptive_threshold");
    o.depth = int(p.getInt("adaptive_depth"));
    o.extraSpp = int(p.getInt("adaptive_spp"));
    const bool boxFilter = o.filter == FilterKind::Box && (o.filterRadius == 0 || o.filterRadius == 0.5);
    if (o.adaptive != AdaptiveMode::Off && !boxFilter)
        throw Error("adaptive=" + a + " reconstructs each pixel from its own samples: use filter=box");
    if (o.adaptive == AdaptiveMode::Supersample && !o.pattern.empty())
        throw Error("adaptive=supersample places its samples on pixel corners and their subdivisions: leave pattern empty");
    return o;
}

ImagePlane::ImagePlane(const ImagePlaneOptions& options, const RenderSettings& settings)
    : opt_(options), settings_(settings), filter_(options.filter, options.filterRadius) {
    const std::uint64_t seed = hashCombine(settings.seed, 0x1a6e);
    if (!opt_.pattern.empty()) patterns_ = makePatternSet(opt_.pattern, settings.spp, seed);
    if (!opt_.pattern.empty() && opt_.adaptive == AdaptiveMode::Stochastic)
        extra_ = makePatternSet(opt_.pattern, opt_.extraSpp, hashCombine(seed, 1));
    if (opt_.plain == PlainSamples::Jittered) jitterGrid_ = squareRootOf(settings.spp);
    const double stored = double(settings.width) * settings.height * settings.spp;
    if (opt_.adaptive == AdaptiveMode::Off && !(filter_.kind() == FilterKind::Box && filter_.radius() == 0.5) && stored > double(1 << 27))
        throw Error("a wide reconstruction filter keeps every sample: " + std::to_string(settings.width) + "x" +
                    std::to_string(settings.height) + " at " + std::to_string(settings.spp) +
                    " spp is more than 2^27 samples; use filter=box or fewer samples");
}

ImagePlane::PixelPatterns ImagePlane::patternsOf(int px, int py) const {
    PixelPatterns p;
    if (patterns_) p.first = patterns_->pattern(patterns_->patternIndex(px, py));
    if (extra_) p.extra = extra_->pattern(extra_->patternIndex(px, py));
    return p;
}

// Wolberg eq. 6.2.1 per colour channel: (Imax - Imin) / (Imax + Imin).
bool ImagePlane::refineStochastic(const std::vector<Rgba>& values) const {
    auto contrast = [&](auto channel) {
        float lo = channel(values.front()), hi = lo;
        for (const Rgba& v : values) lo = std::min(lo, channel(v)), hi = std::max(hi, channel(v));
        return hi + lo > 1e-6f ? (hi - lo) / (hi + lo) : 0.0f;
    };
    const float c = std::max({contrast([](const Rgba& v) { return v.r; }), contrast([](const Rgba& v) { return v.g; }),
                              contrast([](const Rgba& v) { return v.b; }), contrast([](const Rgba& v) { return v.a; })});
    return c > opt_.threshold;
}

// Eq. 6.3.2 at every pixel centre over the samples within the filter radius.
// Where the weights cancel (negative lobes), the pixel's own mean is used.
Image ImagePlane::gather(const std::vector<std::vector<float>>& rows) const {
    const int W = settings_.width, H = settings_.height, spp = settings_.spp;
    const double r = filter_.radius();
    Image image = Image::rgba(W, H);
    tbb::parallel_for(0, H, [&](int py) {
        const double cy = py + 0.5;
        for (int px = 0; px < W; ++px) {
            const double cx = px + 0.5;
            double sum[4] = {0, 0, 0, 0}, wsum = 0;
            for (int y = std::max(0, int(std::floor(cy - r))); y <= std::min(H - 1, int(std::floor(cy + r))); ++y)
                for (int x = std::max(0, int(std::floor(cx - r))); x <= std::min(W - 1, int(std::floor(cx + r))); ++x)
                    for (int k = 0; k < spp; ++k) {
                        const float* s = &rows[y][(std::size_t(x) * spp + k) * 6];
                        const double w = filter_.eval(s[0] - cx, s[1] - cy);
                        if (w == 0) continue;
                        for (int c = 0; c < 4; ++c) sum[c] += w * s[2 + c];
                        wsum += w;
                    }
            float* out = image.pixel(px, py);
            if (std::abs(wsum) > 1e-9 && std::isfinite(wsum)) {
                for (int c = 0; c < 4; ++c) out[c] = float(sum[c] / wsum);
                continue;
            }
            for (int k = 0; k < spp; ++k)
                for (int c = 0; c < 4; ++c) out[c] += rows[py][(std::size_t(px) * spp + k) * 6 + 2 + c] / float(spp);
        }
    });
    return image;
}

}  // namespace weft
