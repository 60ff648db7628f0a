// Counts, scan and batches of core/screen/sample_budget.hpp. Parallel passes work on
// fixed blocks of pixels and combine per-block results in block order, and
// all arithmetic on quotas is integer, so the counts never depend on the
// thread count.
#include "core/screen/sample_budget.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

#include "core/base/error.hpp"
#include "core/base/rng.hpp"

namespace weft {

namespace {

constexpr std::int64_t kMaxBudget = std::int64_t(1) << 40;
constexpr std::size_t kBlock = 32768;  // pixels per parallel block
constexpr int kBuckets = 4096;         // histogram of fractional parts

std::size_t blockCount(std::size_t n) { return (n + kBlock - 1) / kBlock; }

// Runs fn(block, begin, end) over fixed blocks in parallel.
template <class Fn>
void forBlocks(std::size_t n, Fn fn) {
    tbb::parallel_for(std::size_t(0), blockCount(n), [&](std::size_t b) { fn(b, b * kBlock, std::min(n, (b + 1) * kBlock)); });
}

bool isActive(const std::vector<std::uint8_t>& active, std::size_t i) { return active.empty() || active[i] != 0; }

struct Survey {
    std::int64_t active = 0, invalid = 0, infinite = 0;
    float maxFinite = 0;
};

Survey survey(const std::vector<float>& w, const std::vector<std::uint8_t>& active) {
    std::vector<Survey> parts(blockCount(w.size()));
    forBlocks(w.size(), [&](std::size_t b, std::size_t i0, std::size_t i1) {
        Survey s;
        for (std::size_t i = i0; i < i1; ++i) {
            if (!isActive(active, i)) continue;
            ++s.active;
            const float v = w[i];
            if (v == std::numeric_limits<float>::infinity()) ++s.infinite;
            else if (!(v >= 0)) ++s.invalid;
            else s.maxFinite = std::max(s.maxFinite, v);
        }
        parts[b] = s;
    });
    Survey total;
    for (const Survey& s : parts) {
        total.active += s.active, total.invalid += s.invalid, total.infinite += s.infinite;
        total.maxFinite = std::max(total.maxFinite, s.maxFinite);
    }
    return total;
}

// Importance as integer weights: +Inf pixels 1 and the rest 0 when any is
// infinite; else up to 2^bits (<= 2^31) relative to the largest; else 1
// everywhere. Computed where needed rather than stored.
struct Quantiser {
    bool infinite, uniform;
    double scale;
    Quantiser(const Survey& s, int bits)
        : infinite(s.infinite > 0), uniform(s.maxFinite <= 0),
          scale(s.maxFinite > 0 ? std::ldexp(1.0, bits) / double(s.maxFinite) : 0.0) {}
    std::uint32_t operator()(float v) const {
        if (infinite) return v == std::numeric_limits<float>::infinity() ? 1 : 0;
        if (uniform) return 1;
        return v > 0 ? std::uint32_t(double(v) * scale + 0.5) : 0;
    }
};

std::uint64_t weightSum(const std::vector<float>& w, const std::vector<std::uint8_t>& active, const Quantiser& quantise) {
    std::vector<std::uint64_t> parts(blockCount(w.size()), 0);
    forBlocks(w.size(), [&](std::size_t b, std::size_t i0, std::size_t i1) {
        std::uint64_t sum = 0;
        for (std::size_t i = i0; i < i1; ++i)
            if (isActive(active, i)) sum += quantise(w[i]);
        parts[b] = sum;
    });
    std::uint64_t sum = 0;
    for (std::uint64_t v : parts) sum += v;
    return sum;
}

// Order of the leftover samples: larger remainder first, then larger tie
// hash, then lower pixel index. Every key differs, so the order is total.
struct RemainderKey {
    std::uint64_t remainder;
    std::uint32_t hash, index;
    bool operator>(const RemainderKey& o) const {
        if (remainder != o.remainder) return remainder > o.remainder;
        if (hash != o.hash) return hash > o.hash;
        return index < o.index;
    }
};

std::uint32_t tieHash(std::uint64_t seed, std::size_t i) { return std::uint32_t(hashCombine(mix64(seed), i) >> 32); }

struct Quotas {
    std::vector<std::uint64_t> remainder;
    std::vector<std::int64_t> histogram = std::vector<std::int64_t>(kBuckets, 0);
    std::int64_t floors = 0;
    bool overflow = false;  // a pixel's count would not fit 32 bits
};

// Histogram bucket of a remainder: monotone in it (exact integers in, one
// rounding division, a power-of-two scale), so bucket order never
// contradicts remainder order.
int bucketOf(std::uint64_t rem, double toBucket) {
    return int(std::min<double>(kBuckets - 1, double(std::int64_t(rem)) * toBucket));  // rem < 2^63
}

// floor(prod / sum) and prod mod sum, exactly: a floating-point estimate
// (off by at most one for quotients below 2^50) corrected in integers,
// cheaper than a 64-bit division.
void divide(std::uint64_t prod, std::uint64_t sum, double inverse, std::uint64_t& whole, std::uint64_t& rem) {
    whole = std::uint64_t(std::int64_t(double(std::int64_t(prod)) * inverse));  // prod < 2^62: signed conversions are one instruction
    rem = prod - whole * sum;  // modulo 2^64: "negative" when the estimate is high
    while (std::int64_t(rem) < 0) --whole, rem += sum;
    while (rem >= sum) ++whole, rem -= sum;
}

// counts[i] = minimum + floor(free u_i / S); the remainders and their histogram.
Quotas integerQuotas(const std::vector<float>& w, const Quantiser& quantise, const std::vector<std::uint8_t>& active,
                     std::uint64_t sum, std::int64_t freeSamples, int minimum, std::vector<std::uint32_t>& counts) {
    Quotas q;
    q.remainder.resize(w.size());
    std::vector<std::vector<std::int32_t>> hist(blockCount(w.size()));
    std::vector<std::int64_t> floors(hist.size(), 0);
    std::vector<std::uint8_t> overflow(hist.size(), 0);
    const std::uint64_t freeU = std::uint64_t(freeSamples);
    const double toBucket = double(kBuckets) / double(sum), inverse = 1.0 / double(sum);
    forBlocks(w.size(), [&](std::size_t b, std::size_t i0, std::size_t i1) {
        std::vector<std::int32_t> h(kBuckets, 0);
        std::int64_t f = 0;
        std::uint64_t* remainder = q.remainder.data();
        std::uint32_t* c = counts.data();
        const float* importance = w.data();
        const std::uint8_t* act = active.empty() ? nullptr : active.data();
        for (std::size_t i = i0; i < i1; ++i) {
            remainder[i] = 0;
            if (act && !act[i]) continue;
            std::uint64_t whole, rem;
            divide(freeU * quantise(importance[i]), sum, inverse, whole, rem);
            if (whole + std::uint64_t(minimum) >= std::numeric_limits<std::uint32_t>::max()) {
                overflow[b] = 1;
                continue;
            }
            c[i] = std::uint32_t(minimum + std::int64_t(whole));
            f += std::int64_t(whole);
            remainder[i] = rem;
            ++h[std::size_t(bucketOf(rem, toBucket))];
        }
        hist[b] = std::move(h), floors[b] = f;
    });
    for (std::size_t b = 0; b < hist.size(); ++b) {
        q.floors += floors[b];
        q.overflow |= overflow[b] != 0;
        for (int k = 0; k < kBuckets; ++k) q.histogram[std::size_t(k)] += hist[b][std::size_t(k)];
    }
    return q;
}

// One more sample each for the `leftover` pixels with the largest remainders.
void placeLeftover(const Quotas& q, const std::vector<std::uint8_t>& active, std::int64_t leftover, std::uint64_t sum,
                   std::uint64_t seed, std::vector<std::uint32_t>& counts) {
    if (leftover <= 0) return;
    int threshold = kBuckets - 1;
    std::int64_t above = 0;
    while (above + q.histogram[std::size_t(threshold)] < leftover) above += q.histogram[std::size_t(threshold--)];
    const double toBucket = double(kBuckets) / double(sum);
    std::vector<std::vector<RemainderKey>> parts(blockCount(counts.size()));
    forBlocks(counts.size(), [&](std::size_t b, std::size_t i0, std::size_t i1) {
        const std::uint64_t* rem = q.remainder.data();  // locals: no reloads through references
        std::uint32_t* c = counts.data();
        const std::uint8_t* act = active.empty() ? nullptr : active.data();
        for (std::size_t i = i0; i < i1; ++i) {
            if (act && !act[i]) continue;
            const int bucket = bucketOf(rem[i], toBucket);
            c[i] += bucket > threshold ? 1u : 0u;  // branch-free: remainders are noise
            if (bucket == threshold) parts[b].push_back({rem[i], tieHash(seed, i), std::uint32_t(i)});
        }
    });
    std::vector<RemainderKey> candidates;
    for (auto& p : parts) candidates.insert(candidates.end(), p.begin(), p.end());
    const std::size_t need = std::size_t(leftover - above);
    std::nth_element(candidates.begin(), candidates.begin() + std::ptrdiff_t(need - 1), candidates.end(), std::greater<>());
    for (std::size_t k = 0; k < need; ++k) ++counts[candidates[k].index];
}

void checkRequest(const std::vector<float>& importance, const std::vector<std::uint8_t>& active, const BudgetRequest& r) {
    if (r.budget < 0 || r.budget > kMaxBudget)
        throw Error("sample budget " + std::to_string(r.budget) + " is outside [0, 2^40]");
    if (r.minimum < 0) throw Error("minimum samples per pixel must be >= 0 (got " + std::to_string(r.minimum) + ")");
    if (!active.empty() && active.size() != importance.size()) throw Error("sample budget: the active mask does not match the importance map");
    if (importance.size() >= std::numeric_limits<std::uint32_t>::max()) throw Error("sample budget: too many pixels");
}

}  // namespace

SampleCounts apportionSamples(const std::vector<float>& importance, const std::vector<std::uint8_t>& active,
                              const BudgetRequest& r) {
    checkRequest(importance, active, r);
    SampleCounts out;
    out.counts.assign(importance.size(), 0);
    const Survey s = survey(importance, active);
    out.activePixels = s.active, out.invalidImportance = s.invalid, out.infiniteImportance = s.infinite;
    if (s.active == 0) return out;
    out.minimum = int(std::min<std::int64_t>(r.minimum, r.budget / s.active));
    const std::int64_t freeSamples = r.budget - std::int64_t(out.minimum) * s.active;
    const int bits = std::min(31, 62 - int(std::bit_width(std::uint64_t(freeSamples))));
    const Quantiser quantise(s, bits);
    const std::uint64_t sum = weightSum(importance, active, quantise);
    if (sum == 0) throw Error("internal: sample budget weights sum to zero");
    const Quotas q = integerQuotas(importance, quantise, active, sum, freeSamples, out.minimum, out.counts);
    if (q.overflow) throw Error("sample budget " + std::to_string(r.budget) + " puts more than 2^32 - 2 samples on one pixel");
    placeLeftover(q, active, freeSamples - q.floors, sum, r.tieSeed, out.counts);
    out.total = r.budget;
    return out;
}

std::vector<std::int64_t> exclusiveScan(const std::vector<std::uint32_t>& counts) {
    std::vector<std::int64_t> offsets(counts.size() + 1, 0);
    std::vector<std::int64_t> blockSums(blockCount(counts.size()), 0);
    forBlocks(counts.size(), [&](std::size_t b, std::size_t i0, std::size_t i1) {
        std::int64_t s = 0;
        for (std::size_t i = i0; i < i1; ++i) s += counts[i];
        blockSums[b] = s;
    });
    std::int64_t running = 0;
    for (std::int64_t& s : blockSums) running += std::exchange(s, running);
    forBlocks(counts.size(), [&](std::size_t b, std::size_t i0, std::size_t i1) {
        std::int64_t s = blockSums[b];
        for (std::size_t i = i0; i < i1; ++i) offsets[i] = s, s += counts[i];
    });
    offsets.back() = running;
    return offsets;
}

SampleBatches::SampleBatches(const std::vector<std::int64_t>& offsets, std::int64_t batchSize)
    : offsets_(offsets), batchSize_(batchSize) {
    if (offsets.empty()) throw Error("sample batches: no offsets");
    if (batchSize < 1) throw Error("sample batch size must be >= 1 (got " + std::to_string(batchSize) + ")");
    batches_ = (offsets.back() + batchSize - 1) / batchSize;
}

std::int64_t SampleBatches::size(std::int64_t batch) const {
    return std::min(batchSize_, offsets_.back() - begin(batch));
}

void SampleBatches::fill(std::int64_t batch, std::vector<std::uint32_t>& samplePixel) const {
    const std::int64_t b0 = begin(batch);
    samplePixel.resize(std::size_t(size(batch)));
    forEachPixelRun(batch, [&](std::uint32_t pixel, std::int64_t s0, std::int64_t s1) {
        for (std::int64_t s = s0; s < s1; ++s) samplePixel[std::size_t(s - b0)] = pixel;
    });
}

}  // namespace weft
