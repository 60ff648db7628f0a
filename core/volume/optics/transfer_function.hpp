#pragma once
// A 1D transfer function: data value -> (colour, extinction). The data range
// [rangeMin, rangeMax] maps to s in [0, 1]; control points are piecewise
// linear in s. Extinction is per voxel length, so the opacity of a segment
// of length h voxels at constant s is 1 - exp(-extinction(s) * h); colour is
// the emitted colour per unit opacity (emission-absorption model).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace weft {

struct TfPoint {
    double s = 0;                         // position in [0, 1]
    std::array<double, 3> color{1, 1, 1};  // emitted colour
    double extinction = 0;                // per voxel length, >= 0
};

struct TfSample {
    float r, g, b;
    float extinction;
};

class TransferFunction {
public:
    TransferFunction() = default;
    // Points must be sorted by s, with s in [0, 1]; at least one point.
    TransferFunction(double rangeMin, double rangeMax, std::vector<TfPoint> points);

    double rangeMin() const { return rangeMin_; }
    double rangeMax() const { return rangeMax_; }
    const std::vector<TfPoint>& points() const { return points_; }

    // Data value -> normalised scalar, clamped to [0, 1], as a value: the
    // slice loops keep one per sampler, in registers, where a reference to
    // the transfer function would be read again at every sample.
    struct Normalization {
        double min = 0, width = 1;
        double operator()(double value) const {
            if (!std::isfinite(value)) return 0.0;  // NaN voxels read as empty
            return std::clamp((value - min) / width, 0.0, 1.0);
        }
    };
    Normalization normalization() const { return {rangeMin_, rangeMax_ - rangeMin_}; }
    double normalize(double value) const { return normalization()(value); }
    // Exact piecewise-linear evaluation at s in [0, 1] (double precision).
    TfPoint atS(double s) const;
    // Fast lookup through a 4096-entry table, for inner loops (defined
    // here so that every sample loop inlines it).
    TfSample lookup(float value) const {
        float x = value * tableScale_ + tableOffset_;
        if (!(x > 0.0f)) x = 0.0f;  // also maps NaN to 0
        if (x >= float(kTableSize)) return table_[kTableSize];
        const int i = int(x);
        const float t = x - float(i);
        const TfSample& a = table_[i];
        const TfSample& b = table_[i + 1];
        return {a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b),
                a.extinction + t * (b.extinction - a.extinction)};
    }
    // Smallest and largest extinction over the data values [lo, hi]: exact,
    // since extinction is piecewise linear in s (ends and control points).
    std::array<double, 2> extinctionBounds(double lo, double hi) const;
    // Whether lookup() gives exactly zero extinction for every value in
    // [lo, hi], and so for any interpolation of values in it: every table
    // entry its interpolation can read there (one more on each side, for
    // rounding) is zero; where lo == hi, lookup(lo) itself. False for a
    // non-finite bound. Defined here: visibleCells asks it for every cell.
    bool transparentOver(float lo, float hi) const {
        if (!std::isfinite(lo) || !std::isfinite(hi)) return false;
        if (lo == hi) return lookup(lo).extinction == 0.0f;  // interpolating equal values gives that value exactly
        const auto entry = [&](float value) {  // lookup's table position, clamped
            return std::clamp(double(value) * tableScale_ + tableOffset_, 0.0, double(kTableSize));
        };
        const int first = std::max(0, int(entry(std::min(lo, hi))) - 1);
        const int last = std::min(kTableSize, int(entry(std::max(lo, hi))) + 2);
        return visibleBefore_[last + 1] == visibleBefore_[first];
    }

    // The s below which extinction is exactly zero (the control points up to
    // the last one before the first with extinction): 0 where s = 0 already
    // absorbs, infinity where nothing does. A segment between two s below it
    // absorbs nothing and so adds none of the colour, whatever its length
    // (an emission grid's glow is apart from it).
    double zeroExtinctionBelow() const;

    // The default for a bare grid: a smoke-like ramp over [0, maxValue].
    static TransferFunction defaultFor(double minValue, double maxValue);

private:
    static constexpr int kTableSize = 4096;
    void buildTable();
    double rangeMin_ = 0, rangeMax_ = 1;
    std::vector<TfPoint> points_;
    std::vector<TfSample> table_;
    std::vector<int> visibleBefore_;  // entries of table_ before i with non-zero extinction
    float tableScale_ = 1, tableOffset_ = 0;
};

}  // namespace weft
