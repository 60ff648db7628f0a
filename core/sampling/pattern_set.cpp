#include "core/sampling/pattern_set.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "core/base/error.hpp"
#include "core/base/rng.hpp"
#include "core/sampling/generators.hpp"

namespace weft {

namespace {

// Basis names users may shorten ("basis=jitter" reads as jittered).
std::string canonicalName(const std::string& name) { return name == "jitter" ? "jittered" : name; }

void splitOption(const std::string& part, const std::string& text, PatternSpec& spec) {
    const auto eq = part.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == part.size())
        throw Error("pattern '" + text + "': expected key=value after ',' but got '" + part + "'");
    spec.options[part.substr(0, eq)] = part.substr(eq + 1);
}

// Third coordinate of every sample (time, or slice offset): stratified in
// each pixel, sample k of pixel j in stratum sigma_j(k) of spp, and over the
// whole tile, pixel j taking sub-stratum pi_s(j) of M inside stratum s, so
// the tile's M * spp samples fill M * spp strata once each. The random
// permutations decorrelate time from position. Regular sets take centres.
void assignThirdCoordinate(std::vector<PatternPoint>& points, int patterns, int spp, bool centred, std::uint64_t seed) {
    Rng rng(hashCombine(seed, 0x7431ull));
    auto permutation = [&](int n) {
        std::vector<int> p(n);
        std::iota(p.begin(), p.end(), 0);
        for (int i = n; i > 1; --i) std::swap(p[i - 1], p[rng.next() % std::uint64_t(i)]);
        return p;
    };
    std::vector<std::vector<int>> subStratum(spp);
    for (auto& pi : subStratum) pi = permutation(patterns);
    for (int j = 0; j < patterns; ++j) {
        const std::vector<int> sigma = permutation(spp);
        for (int k = 0; k < spp; ++k) {
            const int s = sigma[k];
            const double u = centred ? 0.5 : rng.uniformDouble();
            const double t = (s + (subStratum[s][j] + u) / patterns) / spp;
            points[std::size_t(j) * spp + k].t = std::min(float(t), 0x1.fffffep-1f);
        }
    }
}

float unitFloat(double v) { return std::clamp(float(v - std::floor(v)), 0.0f, 0x1.fffffep-1f); }

// Keller's interleaving: one basis of spp * n * m points over the n x m tile;
// each pixel of the tile takes the points that fall in it. Points keep their
// position inside the pixel; where a pixel holds more than spp, the extra
// ones (latest generated first) move to pixels that hold fewer.
std::vector<PatternPoint> interleave(const std::vector<Vec2>& basis, int n, int m, int spp) {
    const int cells = n * m;
    std::vector<std::vector<PatternPoint>> byCell(cells);
    for (const Vec2& p : basis) {
        const double X = p.x * n, Y = p.y * m;
        const int cx = std::clamp(int(std::floor(X)), 0, n - 1), cy = std::clamp(int(std::floor(Y)), 0, m - 1);
        byCell[cy * n + cx].push_back({unitFloat(X), unitFloat(Y), 0.5f});
    }
    std::vector<PatternPoint> extra;
    for (auto& cell : byCell)
        while (int(cell.size()) > spp) extra.push_back(cell.back()), cell.pop_back();
    std::vector<PatternPoint> out;
    out.reserve(std::size_t(cells) * spp);
    for (auto& cell : byCell) {
        while (int(cell.size()) < spp) cell.push_back(extra.back()), extra.pop_back();
        out.insert(out.end(), cell.begin(), cell.end());
    }
    return out;
}

PatternSet makeInterleaved(const PatternSpec& spec, int spp, std::uint64_t seed) {
    const auto [n, m] = parseTile(spec.arg);
    if (double(spp) * n * m > double(1 << 24))
        throw Error("pattern '" + spec.text + "': " + std::to_string(spp) + " samples per pixel over the tile is more than 2^24 points");
    std::map<std::string, std::string> basisOptions = spec.options;
    std::string basis = "jittered";
    if (auto it = basisOptions.find("basis"); it != basisOptions.end()) basis = canonicalName(it->second), basisOptions.erase(it);
    if (basis == "interleaved") throw Error("pattern '" + spec.text + "': the basis of an interleaved set cannot itself be interleaved");
    const std::vector<Vec2> points = generatePoints(basis, spp * n * m, basisOptions, seed);
    std::vector<PatternPoint> samples = interleave(points, n, m, spp);
    assignThirdCoordinate(samples, n * m, spp, basis == "regular", seed);
    return PatternSet(n, m, spp, std::move(samples));
}

}  // namespace

std::pair<int, int> parseTile(const std::string& text) {
    int n = 0, m = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &n, &x, &m, &extra) != 3 || x != 'x' || n < 1 || m < 1 || n > 256 || m > 256)
        throw Error("tile '" + text + "': expected NxM with N and M in [1, 256], e.g. 4x4");
    return {n, m};
}

PatternSpec parsePatternSpec(const std::string& text) {
    PatternSpec spec;
    spec.text = text;
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1)
        parts.push_back(text.substr(start, comma - start));
    parts.push_back(text.substr(start));
    const std::string& head = parts.front();
    const auto colon = head.find(':');
    spec.name = canonicalName(head.substr(0, colon));
    if (colon != std::string::npos) spec.arg = head.substr(colon + 1);
    if (spec.name.empty()) throw Error("pattern '" + text + "': expected NAME[:ARG][,key=value...]");
    for (std::size_t i = 1; i < parts.size(); ++i) splitOption(parts[i], text, spec);
    return spec;
}

PatternSet::PatternSet(int tileWidth, int tileHeight, int samplesPerPixel, std::vector<PatternPoint> points)
    : tileW_(tileWidth), tileH_(tileHeight), spp_(samplesPerPixel), points_(std::move(points)) {
    if (std::size_t(tileW_) * tileH_ * spp_ != points_.size()) throw Error("pattern set: point count does not fill the tile");
}

std::vector<Vec2> PatternSet::tilePoints() const {
    std::vector<Vec2> out;
    out.reserve(points_.size());
    for (int cy = 0; cy < tileH_; ++cy)
        for (int cx = 0; cx < tileW_; ++cx) {
            const PatternPoint* p = pattern(patternIndex(cx, cy));
            for (int k = 0; k < spp_; ++k) out.push_back({cx + double(p[k].x), cy + double(p[k].y)});
        }
    return out;
}

PatternSet makePatternSet(const PatternSpec& spec, int spp, std::uint64_t seed) {
    if (spp < 1 || spp > (1 << 20)) throw Error("pattern '" + spec.text + "': samples per pixel must be in [1, 1048576]");
    if (spec.name == "interleaved") return makeInterleaved(spec, spp, seed);
    if (!spec.arg.empty())
        throw Error("pattern '" + spec.text + "': only interleaved takes ':ARG' (interleaved:NxM)");
    std::vector<PatternPoint> samples;
    for (const Vec2& p : generatePoints(spec.name, spp, spec.options, seed)) samples.push_back({unitFloat(p.x), unitFloat(p.y), 0.5f});
    assignThirdCoordinate(samples, 1, spp, spec.name == "regular", seed);
    return PatternSet(1, 1, spp, std::move(samples));
}

PatternSet makePatternSet(const std::string& spec, int spp, std::uint64_t seed) {
    return makePatternSet(parsePatternSpec(spec), spp, seed);
}

void validatePatternSpec(const std::string& text) {
    const PatternSpec spec = parsePatternSpec(text);
    if (spec.name == "interleaved") {
        parseTile(spec.arg);
        std::map<std::string, std::string> options = spec.options;
        std::string basis = "jittered";
        if (auto it = options.find("basis"); it != options.end()) basis = canonicalName(it->second), options.erase(it);
        if (basis == "interleaved") throw Error("pattern '" + text + "': the basis of an interleaved set cannot itself be interleaved");
        patternGenerator(basis).options.parse(options);
        return;
    }
    if (!spec.arg.empty()) throw Error("pattern '" + text + "': only interleaved takes ':ARG' (interleaved:NxM)");
    patternGenerator(spec.name).options.parse(spec.options);
}

}  // namespace weft
