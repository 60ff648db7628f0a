#pragma once
// Every position a scene holds (mesh vertices as placed, volumes' boxes,
// camera eyes and targets, point lights) lies within +-kWorldLimit scene
// units on each axis. Ray origins beyond about 1.8e18 are invalid to Embree
// (it aborts), and float positions lose all precision long before that;
// a scene outside the range is refused when it loads.
namespace weft {

constexpr double kWorldLimit = 1e12;

// A volume's voxels, as placed, measure between these on each axis: a
// denormal voxel size (a corrupt transform) made ray marches step forever.
constexpr double kMinVoxelSize = 1e-8, kMaxVoxelSize = 1e8;

}  // namespace weft
