#pragma once
// Pre-integration tables for segments of 1..maxSlices slices, each built
// the first time a render asks for it: a render pays only for the lengths
// it actually uses. Safe to call from parallel loops (threads that need a
// table under construction help build it instead of blocking).
#include <memory>
#include <vector>

#include <tbb/collaborative_call_once.h>

#include "core/volume/preintegration.hpp"

namespace weft {

class SegmentTables {
public:
    SegmentTables(const TransferFunction& tf, double spacing, int maxSlices, int resolution, PreintPrecision precision);
    const PreintegrationTable& forSlices(int slices);
    int builtCount() const;

private:
    const TransferFunction& tf_;
    double spacing_;
    int resolution_;
    PreintPrecision precision_;
    std::unique_ptr<tbb::collaborative_once_flag[]> once_;
    std::vector<std::unique_ptr<PreintegrationTable>> tables_;
};

// Front-to-back compositing of pre-integrated segments (Kraus et al. Fig. 8):
// opacity-weighted colour C and opacity alpha.
struct SegmentCompositor {
    float r = 0, g = 0, b = 0, a = 0;
    void add(const PreintSample& s) {
        const float t = 1.0f - a;
        r += t * s.r, g += t * s.g, b += t * s.b, a += t * s.a;
    }
};

}  // namespace weft
