#pragma once
// SampleBudget: adaptive per-pixel sample counts for a geometry-aware filter
// (Bauszat et al. 2011, section 4), in three steps.
//
// 1. Importance (geometryImportance): the filter's normalisation factor W_p
//    (Eq. 6) over a k x k box window, with the normal and position range
//    weights only (no colour is known before sampling), divided by the number
//    of window pixels inside the image: importance = 1 - W_p / n, in [0, 1).
//    0 where every neighbour looks alike (the filter will average plenty),
//    towards 1 near edges and in busy geometry. Window k covers offsets
//    -(k/2) .. (k-1)/2 in x and y (2x2: -1..0, 4x4: -2..1).
//
// 2. Counts (apportionSamples): a fixed budget (uniform rate x pixels) is
//    split so that every active pixel gets `minimum` and the rest, `free`,
//    follows the importance by the largest-remainder (Hamilton) method: pixel
//    i's quota is free * w_i / sum(w); it gets the quota's integer part, and
//    the samples left over go one each to the pixels with the largest
//    fractional parts. Ties in the fractional part are broken by a hash of
//    (pixel index, tie seed), then by the lower index: deterministic, but
//    not biased towards the top of the image. The counts always sum to the
//    budget exactly (unlike the paper, which drops the rounding remainder).
//    Importance is quantised to integers (up to 31 bits relative to the
//    largest value) so the method is exact integer arithmetic: the same
//    counts on every machine and thread count.
//    Extremes (reported in SampleCounts, never silent):
//    - budget < active pixels x minimum: the minimum is lowered to
//      floor(budget / active pixels) (SampleCounts::minimum says which) and
//      the remaining samples follow the importance as usual;
//    - all importance zero (or below the quantisation step): the free
//      samples are spread uniformly (equal quotas, hash tie-break);
//    - NaN, negative or -Inf importance counts as 0 (invalidImportance);
//    - +Inf importance: those pixels share the free samples equally (the
//      limit of a quota as its weight grows), the others get the minimum
//      (infiniteImportance);
//    - no active pixel: nothing can take a sample; counts are 0 and
//      SampleCounts::total is 0 (the caller sees budget - total unplaced).
//
// 3. Placement: exclusiveScan turns counts into each pixel's first sample
//    index, and SampleBatches cuts the global sample sequence into batches of
//    a fixed size (the paper uses the resolution), filling for each batch a
//    sample-to-pixel buffer; a pixel's samples are contiguous and may span
//    batch boundaries.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/screen/atrous.hpp"

namespace weft {

struct ImportanceSettings {
    int window = 4;                                // k in [2, 10]
    float sigmaNormal = AtrousSettings::kOff;      // as the filter's Eq. 4; kOff: term off
    float sigmaPosition = AtrousSettings::kOff;    // Eq. 5, scene units
};

// Per-pixel importance 1 - W_p / n in [0, 1) (row-major). Guides a sigma
// switches off may be empty. Throws weft::Error for a bad window or sigma.
std::vector<float> geometryImportance(const GeometryGuides& guides, const ImportanceSettings& settings);

struct BudgetRequest {
    std::int64_t budget = 0;   // total samples, >= 0, at most 2^40
    int minimum = 1;           // per active pixel, >= 0
    std::uint64_t tieSeed = 0; // tie-break among equal remainders
};

struct SampleCounts {
    std::vector<std::uint32_t> counts;   // per pixel; 0 for inactive pixels
    std::int64_t total = 0;              // sum of counts: the budget, or 0 without active pixels
    int minimum = 0;                     // minimum actually given to every active pixel
    std::int64_t activePixels = 0;
    std::int64_t invalidImportance = 0;  // active pixels whose NaN/negative importance counted as 0
    std::int64_t infiniteImportance = 0; // active pixels with +Inf importance
};

// `active` (1 = may take samples) may be empty: every pixel active.
SampleCounts apportionSamples(const std::vector<float>& importance, const std::vector<std::uint8_t>& active,
                              const BudgetRequest& request);

// offsets[i] = sum of counts[0..i); offsets.back() = total (size pixels + 1).
std::vector<std::int64_t> exclusiveScan(const std::vector<std::uint32_t>& counts);

// The global sample sequence (pixel 0's samples, then pixel 1's, ...) cut
// into batches of `batchSize` samples (the last one may be shorter).
class SampleBatches {
public:
    SampleBatches(const std::vector<std::int64_t>& offsets, std::int64_t batchSize);

    std::int64_t count() const { return batches_; }
    std::int64_t begin(std::int64_t batch) const { return batch * batchSize_; }
    std::int64_t size(std::int64_t batch) const;
    // The pixel of every sample of `batch`: samplePixel[k] for global sample begin(batch) + k.
    void fill(std::int64_t batch, std::vector<std::uint32_t>& samplePixel) const;
    // fn(pixel, s0, s1) for every pixel with samples [s0, s1) in `batch`
    // (global indices), in parallel; each pixel's run is visited once.
    template <class Fn>
    void forEachPixelRun(std::int64_t batch, Fn fn) const;
    // Index of a global sample among its pixel's samples.
    std::uint32_t indexInPixel(std::int64_t sample, std::uint32_t pixel) const {
        return std::uint32_t(sample - offsets_[pixel]);
    }

private:
    const std::vector<std::int64_t>& offsets_;
    std::int64_t batchSize_, batches_;
};

template <class Fn>
void SampleBatches::forEachPixelRun(std::int64_t batch, Fn fn) const {
    const std::int64_t b0 = begin(batch), b1 = b0 + size(batch);
    const std::size_t first = std::size_t(std::upper_bound(offsets_.begin(), offsets_.end(), b0) - offsets_.begin()) - 1;
    const std::size_t last = std::size_t(std::lower_bound(offsets_.begin(), offsets_.end(), b1) - offsets_.begin());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const std::int64_t s0 = std::max(offsets_[i], b0), s1 = std::min(offsets_[i + 1], b1);
            if (s0 < s1) fn(std::uint32_t(i), s0, s1);
        }
    });
}

}  // namespace weft
