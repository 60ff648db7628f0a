#pragma once
// Pre-integration tables for segments of 1..maxSlices slices, each built
// the first time a render asks for it: a render pays only for the lengths
// it actually uses. Safe to call from parallel loops (threads that need a
// table under construction help build it instead of blocking).
#include <cstdint>
#include <memory>
#include <vector>

#include <tbb/collaborative_call_once.h>

#include "core/volume/optics/preintegration.hpp"

namespace weft {

class SegmentTables {
public:
    // withEmission: every table also holds the emission weights.
    SegmentTables(const TransferFunction& tf, double spacing, int maxSlices, int resolution, PreintPrecision precision,
                  bool withEmission = false);
    const PreintegrationTable& forSlices(int slices);
    int builtCount() const;
    std::int64_t entriesBuilt() const;  // over every table, as PreintegrationTable::entriesBuilt
    bool withEmission() const { return withEmission_; }

private:
    const TransferFunction& tf_;
    double spacing_;
    int resolution_;
    PreintPrecision precision_;
    bool withEmission_;
    std::unique_ptr<tbb::collaborative_once_flag[]> once_;
    std::vector<std::unique_ptr<PreintegrationTable>> tables_;
};

// Front-to-back compositing of pre-integrated segments (Kraus et al. Fig. 8):
// opacity-weighted colour C and opacity alpha.
// Trivial, so that a frame of them can arrive zeroed (zeroedBuffer); write
// `SegmentCompositor c{}` for an empty one.
struct SegmentCompositor {
    float r, g, b, a;
    void add(const PreintSample& s) {
        const float t = 1.0f - a;
        r += t * s.r, g += t * s.g, b += t * s.b, a += t * s.a;
    }
};

// The segments of n overlapping volumes over one stretch of ray, combined
// as one medium whose extinction is their sum. Transmittances multiply, so
// the opacity 1 - prod(1 - a_i) is exact. The colour is the sum of the
// premultiplied colours scaled by a / sum(a_i): exact when one volume
// contributes (it is returned as it is) or all emit the same colour.
// Otherwise each C_i misses the attenuation by the others inside the
// segment: an error of order tau_i tau_j |c_i - c_j| L^2 for a segment of L
// voxels (second order per segment, first order in L over a ray).
inline PreintSample combineMedia(const PreintSample* s, int n) {
    int found = -1, count = 0;
    for (int i = 0; i < n; ++i)
        if (s[i].a > 0 || s[i].r > 0 || s[i].g > 0 || s[i].b > 0) found = i, ++count;
    if (count <= 1) return found < 0 ? (n > 0 ? s[0] : PreintSample{0, 0, 0, 0}) : s[found];
    double T = 1, sumA = 0, r = 0, g = 0, b = 0;
    for (int i = 0; i < n; ++i) T *= 1.0 - s[i].a, sumA += s[i].a, r += s[i].r, g += s[i].g, b += s[i].b;
    const double a = 1.0 - T, scale = sumA > 0 ? a / sumA : 1.0;
    return {float(r * scale), float(g * scale), float(b * scale), float(a)};
}

}  // namespace weft
