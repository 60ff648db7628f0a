#pragma once
// A volume in a scene: an OpenVDB float grid plus its transfer function.
// Grids come from .vdb files or from the procedural generators below.
#include <memory>
#include <string>

#include <openvdb/openvdb.h>

#include "core/scene/camera.hpp"
#include "core/volume/grid/vdb_init.hpp"
#include "core/volume/optics/transfer_function.hpp"

namespace weft {

// What the scattering techniques see in a volume: absorption and scattering
// coefficients (R, G, B) per voxel length per unit density, as vdb_render
// names them, so the same numbers look the same in both, and the
// Henyey-Greenstein anisotropy g. A voxel length is the cube root of a
// voxel's world volume, so scaling a volume keeps its optical depth.
struct VolumeMedium {
    Vec3d absorb{0.1, 0.1, 0.1};
    Vec3d scatter{1.5, 1.5, 1.5};
    double g = 0;
    bool fromScene = false;  // set in the scene file (else the defaults above)
};

struct Volume {
    std::string name;    // grid name
    std::string source;  // file path or "procedural:<kind>"
    openvdb::FloatGrid::ConstPtr grid;
    // Emitted radiance per voxel length (RGB, scene-linear) in the density's
    // index space, from the temperature and emission grids
    // (core/volume/volume_grids.hpp); null when the volume emits nothing.
    openvdb::Vec3SGrid::ConstPtr emission;
    // Eulerian motion (velocity motion blur): the velocity grid in the
    // density's index space, as index displacement per frame (velocity x
    // velocity_scale / fps); a lookup at shutter time t frames from the
    // frame reads every grid at p - motion(p) t (first order). Null when the
    // volume has no velocity grid or the shutter is closed.
    openvdb::Vec3SGrid::ConstPtr motion;
    // How far (index units) a lookup may be advected within the shutter:
    // the largest |motion| x the shutter's largest |t|. The active box is
    // padded by it, so bounds and empty-space skipping see where the
    // volume moves.
    double motionReach = 0;
    double maxMotion = 0;  // the largest |motion|, index units per frame
    // The scattering tint (core/volume/volume_grids.hpp): RGB in [0, 1] per
    // point in the density's index space, 1 outside its active voxels;
    // it multiplies the medium's scattering and moves the rest to
    // absorption, so extinction stays the density's. Null: untinted.
    openvdb::Vec3SGrid::ConstPtr color;
    std::string grids;         // what each role read: "density=density temperature=heat"
    bool gridsPicked = false;  // a bare .vdb's roles, found by their conventional names
    TransferFunction tf;
    float valueMin = 0, valueMax = 0;      // over active values
    openvdb::CoordBBox activeBox;          // active voxels' bounding box, of density and emission (empty() when none)
    VolumeMedium medium;

    // No active voxel and no active tile: renders as nothing at once.
    bool empty() const { return activeBox.empty(); }
    // World length of one voxel (cube root of its volume): the unit of the
    // medium's coefficients and of step lengths given in voxels.
    double voxelLength() const;

    // Index-space box that holds every voxel whose value can be non-zero,
    // padded by one voxel for trilinear support.
    openvdb::CoordBBox indexBox() const;
    BBoxd worldBox() const;
};

// The world box around index box [lo, hi] (its eight corners mapped by xf).
BBoxd worldBoxOf(const openvdb::math::Transform& xf, const Vec3d& lo, const Vec3d& hi);

// The grid moved by an object-to-world map after its own transform (the
// scene file's placement); shares the tree, so nothing is copied.
openvdb::FloatGrid::ConstPtr placeGrid(const openvdb::FloatGrid::ConstPtr& grid, const openvdb::math::Mat4d& objectToWorld);

// The same tree under the identity transform: OpenVDB's ray intersectors
// need uniform voxels, so they march index-space rays through this copy,
// which works for any affine (anisotropic, rotated, sheared) transform.
openvdb::FloatGrid::ConstPtr indexSpaceGrid(const openvdb::FloatGrid& grid);
// indexSpaceGrid of the density (or `visible`, its visibleCells, where
// given), whose active voxels also cover the emission's where the volume
// emits, dilated by the motion's reach where it moves: what an intersector
// must not skip.
openvdb::FloatGrid::ConstPtr occupancyIndexGrid(const Volume& volume, openvdb::FloatGrid::Ptr visible = nullptr);

// Reads one float grid. gridName empty: "density" if present, else the first
// float grid. Errors name the file and list the grids it holds; with a role
// ("temperature") they name it too, and a level set is refused for it.
openvdb::FloatGrid::Ptr readFloatGrid(const std::string& path, const std::string& gridName, const std::string& role = "");
// Reads the vec3s grid `gridName` for `role` ("velocity"); errors as above.
openvdb::Vec3SGrid::Ptr readVec3Grid(const std::string& path, const std::string& gridName, const std::string& role);
// Reads a vec3s or float grid `gridName` for `role` ("color"); errors as above.
openvdb::GridBase::Ptr readFloatOrVec3Grid(const std::string& path, const std::string& gridName, const std::string& role);

// Fills the value range (of the density) and the active bounding box (of
// density and emission); once per volume: both walk the whole tree.
void computeStatistics(Volume& volume);

// Procedural grids (deterministic), sized res^3 voxels, voxel size 1/res so
// the object fills the unit cube [-0.5, 0.5]^3 in world space:
//   "sphere": constant density 1 inside radius 0.4 (closed-form transmittance)
//   "cloud":  a sphere displaced and modulated by fractal value noise
//   "ct":     a CT-like phantom: soft tissue, a vessel with an open lumen
//             along x, a bone-like shell (normalised attenuation, 0..1)
//   "fire":   soot and smoke over a flame rising along +y; its temperature
//             grid (Kelvin, 700 K at the flame's rim to 2000 K in its core)
//             comes from makeProceduralTemperature
openvdb::FloatGrid::Ptr makeProceduralGrid(const std::string& kind, int res, std::uint64_t seed);
openvdb::FloatGrid::Ptr makeProceduralTemperature(int res, std::uint64_t seed);
const char* proceduralKinds();  // "sphere|cloud|ct|fire", for error messages

}  // namespace weft
