#pragma once
// A volume's grids by role. A scene names them ("grids": {"density":
// "density", "temperature": "heat"}, or {"file": ..., "grid": ...} for a
// grid in a file of its own); a bare .vdb is searched for the conventional
// names below and says which it used. Every role reads a float grid of the
// fog-volume (or unknown) class: a level set, or another value type, is an
// error naming the grid. A grid placed under another transform than the
// density's is resampled into the density's index space (OpenVDB's
// resampleToMatch, trilinear), so one index point addresses every grid.
//
// Emission is radiance per voxel length (like the medium's coefficients:
// scaling a volume keeps its look), RGB in the scene's linear space:
//   blackbody_intensity x (T / 1000 K)^4 x colour(T)   T = temperature x temperature_scale + temperature_offset
//   + emission x color x strength
// colour(T) is the Planckian radiator's colour at luminance 1
// (core/volume/optics/blackbody.hpp); the fourth power is the Stefan-Boltzmann law,
// so a hotter region is brighter as well as bluer. Emission comes from the
// active voxels of the temperature and emission grids; inactive ones emit
// nothing. The two are combined once per volume into one RGB grid
// (Volume::emission), so a render looks up one grid for emission.
//
// Velocity (a vec3s grid, world units per second, like Houdini's "vel")
// becomes Volume::motion: index displacement per frame, velocity x
// velocity_scale / fps through the density's inverse Jacobian, so any
// affine voxel shape works. A velocity grid of its own transform is
// resampled into the density's index space as it is (collocated; a
// staggered grid's half-voxel offset is not undone).
//
// Colour (alias albedo; a vec3s grid, or a float grid for a grey tint,
// like Houdini's "Cd") tints the scattering per point, as the "color" of
// Arnold's and Cycles' volume shaders: with the medium's absorb a and
// scatter s (per unit density) and the colour c in [0, 1] at a point,
//   scatter' = s c     absorb' = a + s (1 - c)
// so the extinction a + s is the density's alone. Light that the colour
// withholds is absorbed, not passed through: the majorants, transmittance
// caches and empty-space bounds built from density stay valid, shadows and
// alpha do not change with colour, and only the scattered light is tinted.
// Values are clamped to [0, 1] (an albedo above 1 would create light);
// NaN reads as 1; outside the grid's active voxels the medium is untinted.
#include <map>
#include <string>
#include <vector>

#include <openvdb/openvdb.h>

#include "core/scene/camera.hpp"

namespace weft {

// The roles, in order: density, temperature, emission, velocity, color.
const std::vector<std::string>& gridRoles();
// Other words a scene's "grids" may use for a role: "albedo" for "color".
const std::map<std::string, std::string>& gridRoleAliases();
// A role's conventional grid names, first preferred ("temperature", "heat").
const std::vector<std::string>& conventionalGridNames(const std::string& role);

// Where a role's grid comes from: a grid of the volume's file, or of its own.
struct GridSource {
    std::string file;  // empty: the volume's file
    std::string grid;
};

// Reads the float grid `gridName` of the .vdb at `path` for `role`; errors
// name the file, the grid and the role.
openvdb::FloatGrid::Ptr readRoleGrid(const std::string& path, const std::string& gridName, const std::string& role);

// For a bare .vdb: each role's grid by its conventional names (density:
// `densityName` when given, else "density", else the first float grid);
// roles whose names the file lacks are left out.
std::map<std::string, std::string> pickConventionalGrids(const std::string& path, const std::string& densityName);

// The grid resampled into `target`'s index space when its transform differs
// (unchanged otherwise).
openvdb::FloatGrid::Ptr inIndexSpaceOf(openvdb::FloatGrid::Ptr grid, const openvdb::math::Transform& target);

struct EmissionSettings {
    double temperatureScale = 1, temperatureOffset = 0;  // Kelvin = value x scale + offset
    double blackbodyIntensity = 1;
    Vec3d color{1, 1, 1};  // of the emission grid
    double strength = 1;
};

// Volume::emission from the temperature and emission grids (either may be
// null; both in `transform`'s index space). Finite and non-negative everywhere.
openvdb::Vec3SGrid::Ptr buildEmissionGrid(const openvdb::FloatGrid* temperature, const openvdb::FloatGrid* emission,
                                          const EmissionSettings& settings, const openvdb::math::Transform& transform);

struct MotionSettings {
    double velocityScale = 1;
    double fps = 24;  // frames per second: velocities are per second, shutters in frames
};

// Volume::motion from a velocity grid under the density's transform
// `density` (resampled into its index space when its own differs); sets
// maxMotion to the largest |motion| over every value a lookup can read.
// Non-finite velocities move nothing; a motion longer than kMaxMotionReach
// voxels per frame is shortened to it.
openvdb::Vec3SGrid::Ptr buildMotionGrid(openvdb::Vec3SGrid::Ptr velocity, const openvdb::math::Transform& density,
                                        const MotionSettings& settings, double& maxMotion);

// Volume::color from a colour grid (vec3s, or float: a grey tint) under
// its own transform: each channel clamped to [0, 1], NaN read as 1, every
// inactive value and the background 1, resampled into the density's
// index space `density` when its transform differs.
openvdb::Vec3SGrid::Ptr buildColorGrid(const openvdb::GridBase& color, const openvdb::math::Transform& density);

// The farthest (index units) a lookup is advected while the shutter is open
// (maxMotion x the shutter's largest |t|), capped at kMaxMotionReach so
// that bounds stay finite whatever a broken simulation holds.
constexpr double kMaxMotionReach = 4096;
double motionReachOf(double maxMotion, double shutterOpen, double shutterClose);

}  // namespace weft
