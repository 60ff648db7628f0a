#pragma once
// Fuzz targets: the self-describing volumes `weft convert` imports
// (core/volume/io/volume_import.cpp): NRRD, NumPy .npy and VTK legacy image
// data. The input is the whole file, header and samples; its name gives the
// format. What the header claims is planned (every field checked, the size
// bounded), and when the samples are small enough to read quickly they are
// read into a grid whose values must be finite and whose active voxels must
// lie inside the stated dims.
#include <cmath>

#include "core/volume/io/raw_samples.hpp"
#include "core/volume/io/volume_import.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace weft::fuzz {

// Larger claims are legitimate but take too long per input to fuzz (the
// import tests cover their sizes); the header is still checked.
inline constexpr std::uint64_t kMaxFuzzedSampleBytes = std::uint64_t(1) << 20;

inline Outcome volumeFile(const char* name, const std::uint8_t* data, std::size_t size) {
    const std::string path = writeScratch(name, asText(data, size));
    bool tooLarge = false;
    Outcome o = guarded([&] {
        const VolumeImport im = planImport(path, {});
        if (rawByteCount(im.spec) > kMaxFuzzedSampleBytes) {
            tooLarge = true;
            return;
        }
        const openvdb::FloatGrid::Ptr grid = readVolumeSamples(im.data, im.spec);
        for (auto it = grid->cbeginValueOn(); it; ++it) require(std::isfinite(*it), "finite voxel values");
        const openvdb::Coord dims = im.spec.dims;
        const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
        require(grid->activeVoxelCount() == 0 || (box.min().x() >= 0 && box.min().y() >= 0 && box.min().z() >= 0 &&
                                                  box.max().x() < dims.x() && box.max().y() < dims.y() && box.max().z() < dims.z()),
                "active voxels inside the dims");
    });
    o.skipped = tooLarge;
    return o;
}

inline Outcome nrrdVolume(const std::uint8_t* data, std::size_t size) { return volumeFile("volume.nrrd", data, size); }
inline Outcome npyVolume(const std::uint8_t* data, std::size_t size) { return volumeFile("volume.npy", data, size); }
inline Outcome vtkVolume(const std::uint8_t* data, std::size_t size) { return volumeFile("volume.vtk", data, size); }

}  // namespace weft::fuzz
