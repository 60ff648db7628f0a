#pragma once
// A check of an OpenEXR file's header against the file's own size, run
// before OpenImageIO and OpenEXR read it. OpenEXR trusts the sizes a header
// states: a string attribute claiming 2 GB is allocated and cleared, and a
// data window of 2^31 lines makes an offset table of 16 GB, before the read
// finds the file is 600 bytes long. A corrupt or cut file is refused here in
// microseconds, with one line naming the attribute.
//
// What is checked (the OpenEXR file layout): the magic number; each header's
// attributes (name, type, a size within the bytes left); and that the file
// can hold the offset table its chunk count needs (8 bytes a chunk: the
// chunkCount attribute of a multi-part file, else the data window's lines
// per block or tiles).
#include <cstdint>
#include <string>

namespace weft {

// What the file's headers declare, summed over its parts: a reader would
// allocate about pixelValues floats for them.
struct ExrDeclared {
    std::uint64_t dataPixels = 0;     // data window areas
    std::uint64_t displayPixels = 0;  // display window areas
    std::uint64_t pixelValues = 0;    // data window area times channel count
};

ExrDeclared preflightExr(const std::string& path);

}  // namespace weft
