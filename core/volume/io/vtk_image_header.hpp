#pragma once
// VTK legacy files (.vtk) holding image data: DATASET STRUCTURED_POINTS with
// DIMENSIONS, SPACING (or its old name ASPECT_RATIO) and ORIGIN, then
// POINT_DATA and one SCALARS array of one component, BINARY (big-endian, as
// VTK writes it) or ASCII. Other datasets, cell data, field data and other
// attributes are errors naming the keyword; data after the first SCALARS
// array is left alone.
#include <string>
#include <string_view>

#include "core/volume/io/volume_header.hpp"

namespace weft {

// bytes: the start of the file (at most kMaxHeaderBytes + 1 of it);
// wholeFile: bytes is all of it. `file` names the file in messages.
VolumeHeader parseVtkImageHeader(std::string_view bytes, bool wholeFile, const std::string& file);

}  // namespace weft
