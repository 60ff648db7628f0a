#pragma once
// Pre-integration of the emission-absorption model for ray segments.
//
// A segment of length L voxels is sampled only at its ends, where the scalar
// is s_front and s_back; in between the scalar is assumed to vary linearly.
// With extinction tau(s) and colour c(s) from the transfer function:
//
//   alpha = 1 - exp(-int_0^L tau(s(x)) dx)
//   C     = int_0^L c(s(x)) tau(s(x)) exp(-int_0^x tau(s(u)) du) dx
//
// C is opacity-weighted (premultiplied), composited front to back with
// RayAccumulator::addPremultiplied. For s_front == s_back this reduces to
// C = c (1 - exp(-tau L)), the constant segment of RayAccumulator::add, so
// pre-integrated and plain ray marching agree as the step goes to 0.
//
// tau and c are piecewise linear in s, so the segment splits into pieces on
// which both are linear in x. Per piece the optical depth is exact, and
// integrating by parts reduces the colour to the mean transmittance over the
// piece, which is integrated by Gauss-Legendre quadrature on sub-intervals of
// equal optical depth. Everything is double precision; the table stores the
// results for a grid of (s_front, s_back) per segment length.
//
// Emission (a volume's emission grid, radiance per voxel length, read at
// both ends of a segment) is not a function of s, so it cannot sit in the
// table itself. Assumed linear along the segment, from e_front to e_back,
// its contribution splits into two weights that depend only on s_front,
// s_back and L, through the same transmittance T(x) as the colour:
//
//   E = e_front * W_front + e_back * W_back
//   W_front = int_0^L (1 - x/L) T(x) dx,  W_back = int_0^L (x/L) T(x) dx
//
// An emitting render builds them beside the colour (as W / L, in [0, 1]);
// one without emission builds nothing more. For constant extinction tau
// and e_front == e_back, E = e (1 - exp(-tau L)) / tau, the slab's closed
// form and volume.raymarch's segment.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "core/base/memory/large_buffer.hpp"
#include "core/volume/optics/transfer_function.hpp"

namespace weft {

// Bits8 emulates an RGBA8 table: each entry clamped to [0, 1] and rounded to 1/255.
enum class PreintPrecision { Float32, Bits8 };

struct PreintSample {
    float r, g, b, a;  // opacity-weighted (premultiplied) colour and opacity of one segment
};

// W_front and W_back above, in voxels (the segment's length unit).
struct EmissionWeights {
    float front, back;
};

// Entries are integrated block by block (kPreintBlock x kPreintBlock of one
// length) when a lookup first needs them, so a render pays only for the
// (s_front, s_back) pairs its data hold: a volume's values fill a small
// part of the square, mostly near its diagonal. Every entry depends only on
// its indices, so which thread builds it changes nothing.
constexpr int kPreintBlock = 16;

class PreintegrationTable {
public:
    // Built only for the segment lengths (in voxels) a render uses, e.g.
    // spacing * 2^l for l = 0..lmax. resolution = entries per s axis
    // (s_front and s_back both in [0, 1]). Throws weft::Error for no lengths,
    // a length that is not positive and finite, or resolution outside [2, 4096].
    // withEmission: also the emission weights (lookupEmission).
    PreintegrationTable(const TransferFunction& tf, std::vector<double> lengths, int resolution = 256,
                        PreintPrecision precision = PreintPrecision::Float32, bool withEmission = false);
    ~PreintegrationTable();
    PreintegrationTable(const PreintegrationTable&) = delete;
    PreintegrationTable& operator=(const PreintegrationTable&) = delete;

    int lengthCount() const { return int(lengths_.size()); }
    double length(int index) const;
    int resolution() const { return resolution_; }
    PreintPrecision precision() const { return precision_; }
    bool hasEmission() const { return !emission_.empty(); }

    // s in [0, 1] (tf.normalize(value)); bilinear interpolation between
    // entries; out-of-range s clamped, NaN treated as 0. Builds the entries
    // it reads when they are not built yet. A clear() segment reads nothing
    // (inline, so the slice loops pay a compare for it, not a call).
    PreintSample lookup(int lengthIndex, float sFront, float sBack) const {
        return clearAt(lengthIndex, sFront, sBack) ? PreintSample{0, 0, 0, 0} : read(lengthIndex, sFront, sBack);
    }
    // The same for a table built whole (buildAll), without the per-block
    // check: for loops that look up on every sample.
    PreintSample lookupComplete(int lengthIndex, float sFront, float sBack) const {
        return clearAt(lengthIndex, sFront, sBack) ? PreintSample{0, 0, 0, 0} : readComplete(lengthIndex, sFront, sBack);
    }
    // Whether lookup(any length, sFront, sBack) is exactly zero, known
    // without reading the table: the four entries of both ends' cells lie
    // where the transfer function has no extinction, and a segment there
    // absorbs nothing and adds no colour (noise below a transfer function's first
    // opaque value: most of a CT scan's segments). Uses lookup's own
    // coordinate (s x (resolution - 1)), so it never disagrees with it.
    bool clear(float sFront, float sBack) const { return std::max(sFront, sBack) * float(resolution_ - 1) < clearEntries_; }

    // The exact segment integral in double precision (the reference, also
    // used to fill the table). s outside [0, 1] is clamped, NaN read as 0;
    // a negative or NaN length throws weft::Error, length 0 gives nothing.
    static PreintSample integrateSegment(const TransferFunction& tf, double sFront, double sBack, double length);

    // The emission weights, interpolated as lookup() does; only for a table
    // built withEmission (else weft::Error).
    EmissionWeights lookupEmission(int lengthIndex, float sFront, float sBack) const;
    // The exact emission weights (as integrateSegment; also fills the table).
    static EmissionWeights integrateEmission(const TransferFunction& tf, double sFront, double sBack, double length);

    // Entries integrated so far (of lengthCount() x resolution^2).
    std::int64_t entriesBuilt() const;
    // Integrates every entry not built yet, in parallel: for a render whose
    // lookups cover the table, and after which lookups skip the check.
    void buildAll() const;

private:
    struct Integrator;  // the transfer function's pieces, for building blocks
    // clear() for a length the table holds (any other is read, and refused there).
    bool clearAt(int lengthIndex, float sFront, float sBack) const {
        return lengthIndex >= 0 && lengthIndex < lengthCount() && clear(sFront, sBack);
    }
    // lookup() and lookupComplete() from the table's entries.
    PreintSample read(int lengthIndex, float sFront, float sBack) const;
    PreintSample readComplete(int lengthIndex, float sFront, float sBack) const;
    // Makes sure the block holding entry (lengthIndex, front, back) is built.
    void need(int lengthIndex, int front, int back) const {
        const std::size_t b = blockOf(lengthIndex, front, back);
        if (blockState_[b].load(std::memory_order_acquire) != kBuilt) buildBlock(b);
    }
    // The four entries of a bilinear cell, whose rows and columns may lie in two blocks.
    void needCell(int lengthIndex, int front, int back) const {
        need(lengthIndex, front, back);
        const bool nextRow = (front + 1) % kPreintBlock == 0, nextColumn = (back + 1) % kPreintBlock == 0;
        if (nextRow) need(lengthIndex, front + 1, back);
        if (nextColumn) need(lengthIndex, front, back + 1);
        if (nextRow && nextColumn) need(lengthIndex, front + 1, back + 1);
    }
    std::size_t blockOf(int lengthIndex, int front, int back) const {
        return (std::size_t(lengthIndex) * blocksPerAxis_ + std::size_t(front / kPreintBlock)) * blocksPerAxis_ +
               std::size_t(back / kPreintBlock);
    }
    void buildBlock(std::size_t block) const;
    std::size_t blockCount() const { return lengths_.size() * blocksPerAxis_ * blocksPerAxis_; }
    struct BlockRange {
        int length, front0, front1, back0, back1;  // entries [front0, front1) x [back0, back1) of one length
    };
    BlockRange rangeOf(std::size_t block) const;

    static constexpr std::uint8_t kEmpty = 0, kBuilding = 1, kBuilt = 2;
    std::vector<double> lengths_;
    int resolution_ = 0;
    PreintPrecision precision_ = PreintPrecision::Float32;
    std::size_t blocksPerAxis_ = 0;
    // clear() holds below this table coordinate: the last entry K >= 1 whose
    // s (and every entry's before it) lies below the transfer function's
    // first extinction; -infinity for none, infinity where none absorbs.
    float clearEntries_ = -std::numeric_limits<float>::infinity();
    std::unique_ptr<Integrator> integrator_;
    // Filled block by block on first use (need), hence mutable.
    mutable std::unique_ptr<std::atomic<std::uint8_t>[]> blockState_;
    mutable std::atomic<bool> complete_{false};  // every block built (buildAll)
    mutable FreshBuffer<PreintSample> table_;  // [length][front][back]
    mutable FreshBuffer<EmissionWeights> emission_;  // the same layout, divided by the length; empty without emission
};

}  // namespace weft
