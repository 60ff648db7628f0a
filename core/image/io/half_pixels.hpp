#pragma once
// Float pixels to OpenEXR's half, as the EXR writer stores half channels:
// values beyond +-65504 saturate there (a plain conversion would give Inf)
// and NaN becomes 0. One contiguous pass over the image, eight values at a
// time with the CPU's F16C conversion where it has one; the result equals
// Imath::half's rounding (to nearest, ties to even) value for value.
#include <Imath/half.h>

#include <cstddef>

namespace weft {

void toHalfSaturated(const float* in, std::size_t count, Imath::half* out);

// The same without the SIMD path: the definition the fast one must match.
Imath::half toHalfSaturated(float v);

}  // namespace weft
