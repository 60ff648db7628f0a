#pragma once
// Small VDB files written by the tests themselves (nothing from outside the project).
#include <filesystem>
#include <string>
#include <vector>

namespace weft::test {

// Writes a procedural grid ("sphere" or "cloud") of res^3 voxels, named gridName, to path.
void writeProceduralVdb(const std::filesystem::path& path, const std::string& kind, int res,
                        const std::string& gridName = "density");

// A slab of constant density 1: voxels x, y in [-nxy/2, nxy/2) and z in
// [0, nz), each `voxel` world units. Sampled trilinearly its density ramps
// to 0 over one voxel past each face, so any line across it along z (away
// from the x and y faces) integrates to exactly nz voxels of density.
// alsoNamed: further grids of the same slab in the file ("glow", "heat").
void writeSlabVdb(const std::filesystem::path& path, int nxy, int nz, double voxel, const std::vector<std::string>& alsoNamed = {});

// A density grid with no active voxel (the first frame of a simulation cache).
void writeEmptyVdb(const std::filesystem::path& path);

}  // namespace weft::test
