#pragma once
// NumPy .npy headers (format versions 1.0, 2.0 and 3.0): the magic, the
// header length and the header's dict {'descr', 'fortran_order', 'shape'}.
// weft's samples run x fastest, so a C-ordered array (last axis fastest) of
// shape (Z, Y, X) and a Fortran-ordered one (first axis fastest) of shape
// (X, Y, Z) both map array axis "fastest" to x. Supported dtypes: i1 u1 i2
// u2 i4 u4 f4 f8, either byte order.
#include <string>
#include <string_view>

#include "core/volume/io/volume_header.hpp"

namespace weft {

// bytes: the start of the file (at most kMaxHeaderBytes + 12 of it).
// `file` names the file in messages.
VolumeHeader parseNpyHeader(std::string_view bytes, const std::string& file);

}  // namespace weft
