#include "core/screen/atrous.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "core/base/error.hpp"
#include "core/base/memory/large_buffer.hpp"
#include "core/mesh/mesh_accel.hpp"

namespace weft {

namespace {

constexpr int kMaxLevels = 24;  // taps 2^23 pixels apart already miss any image

bool finite3(const float* c) { return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]); }

// Non-finite colours become missing samples (valid = 0, value 0).
std::vector<std::uint8_t> markValid(float* color, std::size_t size) {
    std::vector<std::uint8_t> valid(size / 3, 1);
    for (std::size_t i = 0; i < valid.size(); ++i)
        if (!finite3(&color[3 * i])) valid[i] = 0, color[3 * i] = color[3 * i + 1] = color[3 * i + 2] = 0;
    return valid;
}

struct Level {
    int width, height, step;
    float invColor, invNormal, invPosition;  // 1/sigma^2, 0 when off
    const GeometryGuides& guides;
    const float* in;
    const std::uint8_t* validIn;
    const float* tapWeight;  // per pixel, multiplies each tap; null: 1
};

// Range-weight exponent between pixels p and q.
float rangeExponent(const Level& l, std::size_t p, std::size_t q, bool colorTerm) {
    float e = 0;
    if (colorTerm) {
        const float* a = &l.in[3 * p];
        const float* b = &l.in[3 * q];
        const float dr = a[0] - b[0], dg = a[1] - b[1], db = a[2] - b[2];
        e += (dr * dr + dg * dg + db * db) * l.invColor;
    }
    if (l.invNormal > 0) e += distance2(l.guides.normal, p, q) * l.invNormal;
    if (l.invPosition > 0) e += distance2(l.guides.position, p, q) * l.invPosition;
    return e;
}

// One output pixel of one level; returns whether it has a value.
bool filterPixel(const Level& l, int x, int y, float* out) {
    const std::size_t p = std::size_t(y) * l.width + x;
    const bool colorTerm = l.invColor > 0 && l.validIn[p];
    double sum[3] = {0, 0, 0}, weightSum = 0;
    for (int j = -2; j <= 2; ++j) {
        const long qy = long(y) + long(j) * l.step;
        if (qy < 0 || qy >= l.height) continue;
        for (int i = -2; i <= 2; ++i) {
            const long qx = long(x) + long(i) * l.step;
            if (qx < 0 || qx >= l.width) continue;
            const std::size_t q = std::size_t(qy) * l.width + std::size_t(qx);
            if (!l.validIn[q]) continue;
            float w = kB3Taps[i + 2] * kB3Taps[j + 2];
            if (l.tapWeight) w *= l.tapWeight[q];
            if (q != p) {
                w *= std::exp(-rangeExponent(l, p, q, colorTerm));
                if (!(w > 0)) continue;  // zero, or NaN from non-finite guides
            }
            const float* c = &l.in[3 * q];
            sum[0] += double(w) * c[0], sum[1] += double(w) * c[1], sum[2] += double(w) * c[2];
            weightSum += w;
        }
    }
    if (!(weightSum > 0)) {
        out[0] = out[1] = out[2] = 0;
        return false;
    }
    for (int k = 0; k < 3; ++k) out[k] = float(sum[k] / weightSum);
    return true;
}

void checkGuide(const VectorPlanes& v, float sigma, std::size_t pixels, const char* name) {
    if (sigma == AtrousSettings::kOff) return;
    for (const auto& plane : v.c)
        if (plane.size() != pixels) throw Error(std::string("atrous: the ") + name + " guide does not cover the image");
}

// Tap weights must be finite and >= 0 (0: a missing sample, see atrous.hpp).
void checkTapWeights(const TapWeights& t, std::size_t pixels) {
    if (t.perPixel.empty()) return;
    if (t.perPixel.size() != pixels) throw Error("atrous: the tap weights do not cover the image");
    for (float w : t.perPixel)
        if (!(w >= 0 && std::isfinite(w))) throw Error("atrous: tap weights must be finite and not negative");
}

}  // namespace

void validate(const AtrousSettings& s) {
    if (s.levels < 0 || s.levels > kMaxLevels)
        throw Error("atrous: levels " + std::to_string(s.levels) + " is outside [0, " + std::to_string(kMaxLevels) + "]");
    auto sigmaOk = [](float v) { return v == AtrousSettings::kOff || (std::isfinite(v) && v > 0); };
    if (!sigmaOk(s.sigmaColor) || !sigmaOk(s.sigmaNormal) || !sigmaOk(s.sigmaPosition))
        throw Error("atrous: sigmas must be positive (or infinite to switch a term off)");
    if (!(s.colorDecay > 0 && s.colorDecay <= 1)) throw Error("atrous: color decay must be in (0, 1]");
}

void atrousFilter(float* color, std::size_t size, int width, int height, const GeometryGuides& guides,
                  const AtrousSettings& s, const TapWeights& tapWeights) {
    validate(s);
    const std::size_t pixels = std::size_t(width) * height;
    if (size != 3 * pixels) throw Error("atrous: colour buffer does not match the image size");
    checkTapWeights(tapWeights, pixels);
    checkGuide(guides.normal, s.sigmaNormal, pixels, "normal");
    checkGuide(guides.position, s.sigmaPosition, pixels, "position");
    // Levels read one buffer and write the other. The second arrives
    // uncleared and is first written by the level's rows on every thread.
    std::vector<std::uint8_t> valid = markValid(color, size);
    FreshBuffer<std::uint8_t> validNext(pixels);
    FreshBuffer<float> next(size);
    float* in = color;
    float* out = next.data();
    std::uint8_t* validIn = valid.data();
    std::uint8_t* validOut = validNext.data();
    float sigmaColor = s.sigmaColor;
    for (int level = 0; level < s.levels; ++level) {
        const bool weighted = !tapWeights.perPixel.empty() && level < tapWeights.levels;
        const Level l{width, height, 1 << level, inverseSquare(sigmaColor), inverseSquare(s.sigmaNormal),
                      inverseSquare(s.sigmaPosition), guides, in, validIn,
                      weighted ? tapWeights.perPixel.data() : nullptr};
        tbb::parallel_for(0, height, [&](int y) {
            enableFastFloatMode();  // every thread the same: tiny weights flush to 0 alike
            for (int x = 0; x < width; ++x) {
                const std::size_t p = std::size_t(y) * width + x;
                validOut[p] = filterPixel(l, x, y, &out[3 * p]) ? 1 : 0;
            }
        });
        std::swap(in, out);
        std::swap(validIn, validOut);
        if (sigmaColor != AtrousSettings::kOff) sigmaColor *= s.colorDecay;
    }
    if (in != color) std::copy(next.begin(), next.end(), color);  // an odd number of levels ended in `next`
}

namespace {

std::vector<std::string> layerChannels(const std::string& layer, const char* a, const char* b, const char* c) {
    const std::string prefix = layer.empty() ? "" : layer + ".";
    return {prefix + a, prefix + b, prefix + c};
}

// One channel as a plane; empty, and its name added to `missing`, when the image lacks it.
std::vector<float> readChannel(const Image& image, const std::string& name, std::string& missing) {
    const int ch = image.channelIndex(name);
    if (ch < 0) {
        missing += (missing.empty() ? "" : ", ") + name;
        return {};
    }
    std::vector<float> plane(std::size_t(image.width()) * image.height());
    for (std::size_t i = 0; i < plane.size(); ++i) plane[i] = image.data()[i * image.channelCount() + ch];
    return plane;
}

// Reads three channels as planes; names the missing ones in `missing`.
VectorPlanes readPlanes(const Image& image, const std::vector<std::string>& names, std::string& missing) {
    VectorPlanes v;
    for (int k = 0; k < 3; ++k) v.c[k] = readChannel(image, names[k], missing);
    return v;
}

// Tap weights on every level from one channel ('' = none).
TapWeights readTapWeights(const Image& image, const std::string& channel, std::string& missing) {
    if (channel.empty()) return {};
    return TapWeights{readChannel(image, channel, missing), TapWeights::kAllLevels};
}

}  // namespace

void atrousFilterImage(Image& image, const std::string& layer, const std::string& normalLayer,
                       const std::string& positionLayer, const AtrousSettings& s, const std::string& weightChannel) {
    validate(s);
    std::string missing;
    const auto colorNames = layer.empty() ? std::vector<std::string>{"R", "G", "B"} : layerChannels(layer, "R", "G", "B");
    const VectorPlanes rgb = readPlanes(image, colorNames, missing);
    GeometryGuides g{image.width(), image.height(), {}, {}};
    if (s.sigmaNormal != AtrousSettings::kOff) g.normal = readPlanes(image, layerChannels(normalLayer, "X", "Y", "Z"), missing);
    if (s.sigmaPosition != AtrousSettings::kOff) g.position = readPlanes(image, layerChannels(positionLayer, "X", "Y", "Z"), missing);
    const TapWeights weights = readTapWeights(image, weightChannel, missing);
    if (!missing.empty())
        throw Error("the image has no channel " + missing + " (the normal and position guides are needed only while their sigmas are on)");
    const std::size_t pixels = std::size_t(image.width()) * image.height();
    std::vector<float> color(3 * pixels);
    for (std::size_t i = 0; i < pixels; ++i) color[3 * i] = rgb.c[0][i], color[3 * i + 1] = rgb.c[1][i], color[3 * i + 2] = rgb.c[2][i];
    atrousFilter(color, image.width(), image.height(), g, s, weights);
    const int stride = image.channelCount();
    for (int k = 0; k < 3; ++k) {
        const int ch = image.channelIndex(colorNames[k]);
        for (std::size_t i = 0; i < pixels; ++i) image.data()[i * stride + ch] = color[3 * i + k];
    }
}

}  // namespace weft
