// weft pattern SPEC --count N [--tile NxM] [--seed S] -o periodogram.exr
//
// Analyses a pattern set (core/sampling/pattern_set.hpp): N samples per
// pixel over a tile of pixels (the set's own tile for interleaved:NxM, else
// --tile, else one pixel; a plain pattern is repeated in every pixel of the
// tile, as the method of dependent tests does). Prints the L2-star
// discrepancy (Warnock) of the tile's points scaled to the unit square, and
// the nearest-neighbour distances on the torus; writes the periodogram
// averaged over --seeds seeds as an EXR (DC at the centre, frequencies in
// cycles per tile), its radial average as CSV, and optionally the points
// (CSV) and a preview PNG (points beside the periodogram).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/base/files/atomic_file.hpp"
#include "core/base/error.hpp"
#include "core/image/io/image_io.hpp"
#include "core/sampling/generators.hpp"
#include "core/sampling/pattern_analysis.hpp"
#include "core/sampling/pattern_set.hpp"
#include "plugins/host/command.hpp"

namespace weft {

namespace {

struct PatternOptions {
    std::string spec, output, csv, pointsCsv, preview, tile;
    int count = 16, seeds = 32, freq = 0;
    std::uint64_t seed = 0;
    bool list = false;
};

// The tile's points scaled to the unit square.
std::vector<Vec2> unitPoints(const PatternOptions& o, std::uint64_t seed, int& tileW, int& tileH) {
    const PatternSpec spec = parsePatternSpec(o.spec);
    const PatternSet set = makePatternSet(spec, o.count, seed);
    tileW = set.tileWidth(), tileH = set.tileHeight();
    if (!o.tile.empty()) {
        const auto [n, m] = parseTile(o.tile);
        if (spec.name == "interleaved" && (n != tileW || m != tileH))
            throw Error("--tile " + o.tile + " differs from the interleaved set's own tile " + spec.arg);
        tileW = n, tileH = m;
    }
    std::vector<Vec2> out;
    for (int y = 0; y < tileH; ++y)
        for (int x = 0; x < tileW; ++x)
            for (int k = 0; k < o.count; ++k) {
                const PatternPoint& p = set.sample(x, y, k);
                out.push_back({(x + double(p.x)) / tileW, (y + double(p.y)) / tileH});
            }
    return out;
}

std::string radialCsv(const std::vector<RadialBin>& bins, int tileW) {
    std::string out = "frequency_per_tile,frequency_per_pixel,power,anisotropy,bins\n";
    char line[160];
    for (const RadialBin& b : bins) {
        std::snprintf(line, sizeof line, "%d,%.6g,%.8g,%.6g,%d\n", b.radius, double(b.radius) / tileW, b.power, b.anisotropy, b.count);
        out += line;
    }
    return out;
}

Image spectrumImage(const std::vector<double>& spectrum, int R) {
    const int side = 2 * R + 1;
    Image img(side, side, {"R", "G", "B"});
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = float(spectrum[std::size_t(y) * side + x]);
    return img;
}

// Points (left) beside the periodogram (right), DC removed, power 4 -> white.
Image previewImage(const std::vector<Vec2>& points, const Image& spectrum) {
    const int side = spectrum.width();
    Image img = Image::rgba(2 * side + 4, side);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = 1.0f, img.at(side + 4 + x, y, c) = spectrum.at(x, y, c) / 4;
            img.at(x, y, 3) = img.at(side + 4 + x, y, 3) = 1;
        }
    for (int c = 0; c < 3; ++c) img.at(side + 4 + side / 2, side / 2, c) = 0;
    for (const Vec2& p : points) {
        const int x = std::min(int(p.x * side), side - 1), y = std::min(int(p.y * side), side - 1);
        for (int c = 0; c < 3; ++c) img.at(x, y, c) = 0;
    }
    return img;
}

void printSummary(const PatternOptions& o, const std::vector<Vec2>& pts, int tileW, int tileH) {
    std::printf("pattern %s: %d per pixel, tile %dx%d, %zu points, seed %llu\n", o.spec.c_str(), o.count, tileW, tileH,
                pts.size(), (unsigned long long)o.seed);
    if (pts.size() <= 65536) std::printf("L2-star discrepancy  %.9g\n", l2StarDiscrepancy(pts));
    else std::printf("L2-star discrepancy  (not computed above 65536 points: O(N^2))\n");
    if (pts.size() >= 2) {
        const NeighbourDistances d = neighbourDistances(pts);
        const double hex = hexagonalDistance(int(pts.size()));
        std::printf("nearest neighbour    min %.6g  mean %.6g  max %.6g  (x hexagonal packing: %.3f %.3f %.3f)\n", d.min,
                    d.mean, d.max, d.min / hex, d.mean / hex, d.max / hex);
    }
    if (pts.size() <= 64) {
        std::printf("points (x y, unit square):\n");
        for (const Vec2& p : pts) std::printf("  %.9f %.9f\n", p.x, p.y);
    }
}

void runPattern(const PatternOptions& o) {
    if (o.list) {
        for (const PatternGeneratorInfo* g : patternGenerators().all())
            std::printf("%-16s %s\n%s", g->name.c_str(), g->summary.c_str(), g->options.helpText().c_str());
        std::printf("%-16s %s\n", "interleaved:NxM", "Keller-Heidrich interleaving of a basis over an NxM pixel tile; basis=NAME "
                    "(default jittered) and the basis's own options");
        return;
    }
    if (o.spec.empty()) throw Error("weft pattern: name a pattern (weft pattern --list)");
    if (!o.output.empty()) checkOutputPath(o.output, "output");
    if (!o.preview.empty()) checkOutputPath(o.preview, "preview");
    int tileW = 1, tileH = 1;
    const std::vector<Vec2> pts = unitPoints(o, o.seed, tileW, tileH);
    const int R = o.freq > 0 ? o.freq : std::clamp(2 * int(std::ceil(std::sqrt(double(pts.size())))), 16, 128);
    const double work = double(pts.size()) * (2 * R + 1) * (2 * R + 1) * o.seeds;
    if (!o.output.empty() && work > 2e10)
        throw Error("periodogram of " + std::to_string(pts.size()) + " points over " + std::to_string(2 * R + 1) + "^2 frequencies and " +
                    std::to_string(o.seeds) + " seeds is too much work; lower --seeds or --freq");
    printSummary(o, pts, tileW, tileH);
    if (!o.pointsCsv.empty()) {
        std::string text = "x,y\n";
        char line[64];
        for (const Vec2& p : pts) std::snprintf(line, sizeof line, "%.9f,%.9f\n", p.x, p.y), text += line;
        writeTextAtomically(o.pointsCsv, text, "points");
    }
    if (o.output.empty()) return;
    std::vector<double> sum;
    for (int s = 0; s < o.seeds; ++s) {
        int w = 0, h = 0;
        const std::vector<double> p = periodogram(s == 0 ? pts : unitPoints(o, o.seed + s, w, h), R);
        if (sum.empty()) sum.assign(p.size(), 0.0);
        for (std::size_t i = 0; i < p.size(); ++i) sum[i] += p[i] / o.seeds;
    }
    const Image spectrum = spectrumImage(sum, R);
    writeExr(spectrum, o.output, {{"weft:pattern", o.spec}, {"weft:count", std::to_string(o.count)},
                                  {"weft:seeds", std::to_string(o.seeds)}, {"weft:tile", std::to_string(tileW) + "x" + std::to_string(tileH)}});
    std::string csv = o.csv;
    if (csv.empty()) csv = o.output.substr(0, o.output.size() - 4) + "_radial.csv";
    writeTextAtomically(csv, radialCsv(radialAverage(sum, R), tileW), "csv");
    if (!o.preview.empty()) writePreview(previewImage(pts, spectrum), o.preview);
    std::printf("periodogram          %s (%dx%d, %d seeds), radial average %s\n", o.output.c_str(), 2 * R + 1, 2 * R + 1,
                o.seeds, csv.c_str());
}

const CommandRegistrar registrar{{"pattern", 40, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("pattern", "analyse a sample pattern: discrepancy, distances, periodogram");
    auto o = std::make_shared<PatternOptions>();
    cmd->add_option("name", o->spec, "pattern spec: NAME[:NxM][,key=value...] (--list)");
    cmd->add_option("--count", o->count, "samples per pixel")->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--tile", o->tile, "analyse an NxM tile of pixels (a plain pattern repeats in each)");
    cmd->add_option("--seed", o->seed, "seed of the printed set (the periodogram uses seed..seed+seeds-1)");
    cmd->add_option("--seeds", o->seeds, "sets averaged in the periodogram")->check(CLI::Range(1, 100000));
    cmd->add_option("--freq", o->freq, "periodogram half-size R: frequencies -R..R per tile (default 2 sqrt(points) in [16, 128])")
        ->check(CLI::Range(1, 1024));
    cmd->add_option("-o,--output", o->output, "periodogram EXR");
    cmd->add_option("--csv", o->csv, "radially averaged spectrum (default: OUTPUT with _radial.csv)");
    cmd->add_option("--points", o->pointsCsv, "write the points of the printed set as CSV");
    cmd->add_option("--preview", o->preview, "PNG of the points beside the periodogram");
    cmd->add_flag("--list", o->list, "list the pattern generators and their options");
    cmd->callback([o] { runPattern(*o); });
}}};

}  // namespace

}  // namespace weft
