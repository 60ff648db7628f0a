#pragma once
// What a self-describing volume file's header says: the spec of its
// samples, which parts of that spec the header states (so that convert's
// options may fill in the rest but not contradict it), and where and how
// the samples are stored. The header readers (nrrd_header.hpp,
// npy_header.hpp, vtk_image_header.hpp) are functions from the header's
// bytes to this, so a fuzz target can call them without files.
#include <cstdint>
#include <string>
#include <string_view>

#include "core/volume/io/raw_volume.hpp"

namespace weft {

struct StatedFields {
    bool dims = false, type = false, byteOrder = false, spacing = false, origin = false, direction = false;
};

struct VolumeHeader {
    RawVolumeSpec spec;
    StatedFields stated;
    SampleEncoding encoding = SampleEncoding::Raw;
    std::uint64_t dataOffset = 0;  // where the samples start, counted from the first byte of the header
    bool trailingAllowed = false;  // other data may follow the samples
};

// No header weft reads is longer: a file that has not finished its header
// by then is not one.
inline constexpr std::size_t kMaxHeaderBytes = std::size_t(1) << 20;

// The line of a text header (NRRD, VTK) that starts at `pos`, without its
// LF or CR LF; `pos` moves to the next line. When only the first
// kMaxHeaderBytes of the file were read (wholeFile false) and no line end is
// left, the header is too long: "<file>: <format> header does not end within ...".
std::string_view nextHeaderLine(std::string_view bytes, std::size_t& pos, bool wholeFile, const std::string& file,
                                const char* format);

// The header's own size summary for messages: "the header's 5x4x3 i16".
std::string headerDescription(const RawVolumeSpec& spec);

}  // namespace weft
