#pragma once
// What `weft convert` reads: a headerless raw file described by options, or
// a self-describing file found by its extension (.nrrd, .nhdr, .npy, .vtk)
// whose header describes it. Options complement a header (the grid name,
// the background, an origin a format cannot state) but must not contradict
// it.
#include <optional>
#include <string>

#include "core/volume/io/raw_volume.hpp"

namespace weft {

// Convert's options as typed; nullopt when not given.
struct ImportOptions {
    std::optional<std::string> dims, type, endian, spacing, origin, direction, background;
    std::string grid = "density";
};

struct VolumeImport {
    std::string format;  // "raw", "nrrd", "npy", "vtk"
    RawVolumeSpec spec;
    RawDataSource data;
};

// Checks every option, reads the header if there is one, and says where the
// samples are. Throws weft::Error naming the option, file or field.
VolumeImport planImport(const std::string& path, const ImportOptions& options);

}  // namespace weft
