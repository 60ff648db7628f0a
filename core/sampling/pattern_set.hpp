#pragma once
// PatternSet: M basis patterns of sample positions on the unit torus plus the
// interleaving map from pixel (x, y) to a pattern index over an n x m tile
// (Keller & Heidrich 2001). The same pattern in every pixel (M = 1) is the
// method of dependent tests; an interleaved set gives neighbouring pixels
// different patterns while sample k of pattern j still lies on a regular grid
// of spacing (n, m) pixels.
//
// Sets are named by a spec a user types: NAME[:ARG][,key=value...], e.g.
//   jittered                      the same jittered pattern in every pixel
//   poisson,radius=0.7            Poisson-disk, relative radius 0.7
//   interleaved:4x4,basis=lp      one basis of 16*spp points over a 4x4 tile
// Every set is a pure function of (spec, samples per pixel, seed).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace weft {

struct Vec2 {
    double x = 0, y = 0;
};

// One sample: position inside the pixel in [0, 1)^2 and a third coordinate t
// in [0, 1) (time for motion blur, the slice offset for volumes).
struct PatternPoint {
    float x = 0.5f, y = 0.5f, t = 0.5f;
};

struct PatternSpec {
    std::string name;                           // generator name or "interleaved"
    std::string arg;                            // "4x4" for interleaved
    std::map<std::string, std::string> options;  // key=value after commas
    std::string text;                           // as typed
};

// Parses NAME[:ARG][,key=value...]; malformed text is an error naming it.
PatternSpec parsePatternSpec(const std::string& text);

class PatternSet {
public:
    PatternSet() = default;
    PatternSet(int tileWidth, int tileHeight, int samplesPerPixel, std::vector<PatternPoint> points);

    int tileWidth() const { return tileW_; }
    int tileHeight() const { return tileH_; }
    int patternCount() const { return tileW_ * tileH_; }
    int samplesPerPixel() const { return spp_; }
    // Pattern of pixel (x, y): the interleaving map over the tile (any sign of x, y).
    int patternIndex(int x, int y) const { return wrap(y, tileH_) * tileW_ + wrap(x, tileW_); }
    const PatternPoint* pattern(int index) const { return points_.data() + std::size_t(index) * spp_; }
    const PatternPoint& sample(int x, int y, int k) const { return pattern(patternIndex(x, y))[k]; }
    // Every point of the tile in tile coordinates, [0, n) x [0, m).
    std::vector<Vec2> tilePoints() const;

private:
    static int wrap(int v, int n) { return ((v % n) + n) % n; }
    int tileW_ = 1, tileH_ = 1, spp_ = 0;
    std::vector<PatternPoint> points_;  // pattern j's samples at [j * spp, (j + 1) * spp)
};

// Builds the set a spec names with spp samples in every pixel.
PatternSet makePatternSet(const std::string& spec, int samplesPerPixel, std::uint64_t seed);
PatternSet makePatternSet(const PatternSpec& spec, int samplesPerPixel, std::uint64_t seed);

// Checks a spec without building it (parameter validation before a render).
void validatePatternSpec(const std::string& spec);

// "NxM" -> (N, M), each in [1, 256].
std::pair<int, int> parseTile(const std::string& text);

}  // namespace weft
