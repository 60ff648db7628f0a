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
#include <cstddef>
#include <vector>

#include "core/base/large_buffer.hpp"
#include "core/volume/transfer_function.hpp"

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

class PreintegrationTable {
public:
    // Built only for the segment lengths (in voxels) a render uses, e.g.
    // spacing * 2^l for l = 0..lmax. resolution = entries per s axis
    // (s_front and s_back both in [0, 1]). Throws weft::Error for no lengths,
    // a length that is not positive and finite, or resolution outside [2, 4096].
    // withEmission: also the emission weights (lookupEmission).
    PreintegrationTable(const TransferFunction& tf, std::vector<double> lengths, int resolution = 256,
                        PreintPrecision precision = PreintPrecision::Float32, bool withEmission = false);

    int lengthCount() const { return int(lengths_.size()); }
    double length(int index) const;
    int resolution() const { return resolution_; }
    PreintPrecision precision() const { return precision_; }
    bool hasEmission() const { return !emission_.empty(); }

    // s in [0, 1] (tf.normalize(value)); bilinear interpolation between
    // entries; out-of-range s clamped, NaN treated as 0.
    PreintSample lookup(int lengthIndex, float sFront, float sBack) const;

    // The exact segment integral in double precision (the reference, also
    // used to fill the table). s outside [0, 1] is clamped, NaN read as 0;
    // a negative or NaN length throws weft::Error, length 0 gives nothing.
    static PreintSample integrateSegment(const TransferFunction& tf, double sFront, double sBack, double length);

    // The emission weights, interpolated as lookup() does; only for a table
    // built withEmission (else weft::Error).
    EmissionWeights lookupEmission(int lengthIndex, float sFront, float sBack) const;
    // The exact emission weights (as integrateSegment; also fills the table).
    static EmissionWeights integrateEmission(const TransferFunction& tf, double sFront, double sBack, double length);

private:
    std::vector<double> lengths_;
    int resolution_ = 0;
    PreintPrecision precision_ = PreintPrecision::Float32;
    FreshBuffer<PreintSample> table_;  // [length][front][back]; filled whole in parallel
    FreshBuffer<EmissionWeights> emission_;  // the same layout, divided by the length; empty without emission
};

}  // namespace weft
