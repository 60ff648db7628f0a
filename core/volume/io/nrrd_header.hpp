#pragma once
// NRRD headers (teem's "nearly raw raster data", NRRD0001..NRRD0005): the
// fields weft needs to read a 3-D scalar volume stored raw or gzip, attached
// (.nrrd: the samples follow the blank line ending the header) or detached
// (.nhdr: "data file:" names them, relative to the header). Anything else
// (other encodings, several data files, dimensions other than 3, 64-bit
// integers) is an error naming the field and its value.
#include <string>
#include <string_view>

#include "core/volume/io/volume_header.hpp"

namespace weft {

struct NrrdHeader {
    VolumeHeader volume;   // dataOffset: the header's length when attached
    std::string dataFile;  // as written; empty when the samples are attached
    std::int64_t lineSkip = 0;  // lines of the data file before the samples
    std::int64_t byteSkip = 0;  // bytes after those (-1: the samples end the file); after decompression for gzip
};

// bytes: the start of the file (at most kMaxHeaderBytes + 1 of it);
// wholeFile: bytes is all of it. `file` names the file in messages.
NrrdHeader parseNrrdHeader(std::string_view bytes, bool wholeFile, const std::string& file);

}  // namespace weft
