// point_diffusion: Mitchell's point-diffusion sampling (Wolberg 6.3.4).
// Floyd-Steinberg error diffusion of a constant grey level on a grid with
// `density` cells per point (16: four times denser than the display grid in
// each direction) picks grid cells as points; the diffused error spreads
// them out with a blue-noise spectrum. Scanning is serpentine and wraps
// round the torus; a small seeded perturbation of the threshold and a seeded
// shift of the whole set make each seed a different pattern. The grey level
// is found by bisection so that the count comes out right; any remainder is
// removed or added at seeded random cells so exactly count points result.
#include <algorithm>
#include <cmath>

#include "core/base/error.hpp"
#include "core/base/rng.hpp"
#include "core/sampling/generators.hpp"

namespace weft {

namespace {

// Cells chosen by error diffusion of `grey` (row-major G x G mask).
std::vector<char> diffuse(int G, double grey, const std::vector<float>& thresholdNoise) {
    std::vector<char> on(std::size_t(G) * G, 0);
    std::vector<double> err(std::size_t(G) * G, 0.0);
    auto at = [&](int x, int y) -> double& { return err[std::size_t((y + G) % G) * G + (x + G) % G]; };
    for (int y = 0; y < G; ++y) {
        const bool leftToRight = (y % 2) == 0;
        const int dir = leftToRight ? 1 : -1;
        for (int i = 0; i < G; ++i) {
            const int x = leftToRight ? i : G - 1 - i;
            const std::size_t c = std::size_t(y) * G + x;
            const double v = grey + err[c];
            const bool dot = v > 0.5 + thresholdNoise[c];
            on[c] = dot;
            const double e = v - (dot ? 1.0 : 0.0);
            at(x + dir, y) += e * 7 / 16;
            at(x - dir, y + 1) += e * 3 / 16;
            at(x, y + 1) += e * 5 / 16;
            at(x + dir, y + 1) += e * 1 / 16;
        }
    }
    return on;
}

long countOn(const std::vector<char>& on) { return std::count(on.begin(), on.end(), 1); }

// Adds or removes seeded random cells until exactly count are on.
void fixCount(std::vector<char>& on, long count, Rng& rng) {
    long have = countOn(on);
    while (have != count) {
        const std::size_t c = rng.next() % on.size();
        if (have > count && on[c]) on[c] = 0, --have;
        else if (have < count && !on[c]) on[c] = 1, ++have;
    }
}

std::vector<Vec2> pointDiffusion(int count, double density, std::uint64_t seed) {
    const int G = std::max(2, int(std::lround(std::sqrt(density * count))));
    if (std::size_t(G) * G < std::size_t(count)) throw Error("point_diffusion: density too low for the point count");
    Rng rng(seed);
    std::vector<float> noise(std::size_t(G) * G);
    for (float& n : noise) n = 0.1f * (rng.uniform() - 0.5f);
    double lo = 0, hi = std::min(1.0, 2.0 * count / (double(G) * G));
    std::vector<char> best = diffuse(G, hi, noise);
    for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (lo + hi);
        std::vector<char> on = diffuse(G, mid, noise);
        const long n = countOn(on);
        if (std::abs(n - count) < std::abs(countOn(best) - count)) best = on;
        if (n == count) break;
        (n < count ? lo : hi) = mid;
    }
    fixCount(best, count, rng);
    const double sx = rng.uniformDouble(), sy = rng.uniformDouble();
    std::vector<Vec2> out;
    out.reserve(count);
    for (int y = 0; y < G; ++y)
        for (int x = 0; x < G; ++x)
            if (best[std::size_t(y) * G + x]) {
                const double px = (x + 0.5) / G + sx, py = (y + 0.5) / G + sy;
                out.push_back({px - std::floor(px), py - std::floor(py)});
            }
    return out;
}

}  // namespace

void registerPointDiffusionGenerator(PatternGeneratorRegistry& r) {
    r.add({"point_diffusion", "Mitchell's point diffusion: Floyd-Steinberg error diffusion on a fine grid",
           ParamTable("pattern point_diffusion",
                      {floatParam("density", 16, 4, 256, "grid cells per point (16: 4x4 cells for each point)")}),
           [](int count, const ParamSet& o, std::uint64_t seed) { return pointDiffusion(count, o.getFloat("density"), seed); }});
}

}  // namespace weft
