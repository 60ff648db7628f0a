#pragma once
// Small VDB files written by the tests themselves (nothing from outside the project).
#include <filesystem>
#include <string>

namespace weft::test {

// Writes a procedural grid ("sphere" or "cloud") of res^3 voxels, named gridName, to path.
void writeProceduralVdb(const std::filesystem::path& path, const std::string& kind, int res,
                        const std::string& gridName = "density");

// A density grid with no active voxel (the first frame of a simulation cache).
void writeEmptyVdb(const std::filesystem::path& path);

}  // namespace weft::test
