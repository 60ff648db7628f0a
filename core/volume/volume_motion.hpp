#pragma once
// Velocity motion blur as every technique that renders it sees a moving
// volume (Volume::motion, an open shutter): at shutter time t (frames from
// the frame) each of the volume's grids is read at p - motion(p) t, p in
// the density's index space (first-order backward advection). The bounds
// that make this safe are built once per scene: Volume::activeBox and
// occupancyIndexGrid are padded by Volume::motionReach (core/scene/
// scene_loader.cpp, core/volume/volume.cpp), and majorants over bricks are
// dilated by it (dilatedBrickBounds below).
#include <cmath>
#include <optional>

#include <openvdb/openvdb.h>

#include "core/volume/grid/leaf_sampler.hpp"
#include "core/volume/volume.hpp"

namespace weft {

// One thread's lookups of one volume's motion; built in place (the sampler
// points at the accessor), never copied.
class MotionLookup {
public:
    explicit MotionLookup(const openvdb::Vec3SGrid& motion)
        : accessor_(motion.getConstAccessor()), sampler_(accessor_, motion.transform()) {}
    MotionLookup(const MotionLookup&) = delete;
    MotionLookup& operator=(const MotionLookup&) = delete;

    // Where the grids are read for index point p at shutter time `time`.
    openvdb::Vec3d advected(const openvdb::Vec3d& p, double time) { return p - openvdb::Vec3d(sampler_.isSample(p)) * time; }

private:
    openvdb::Vec3SGrid::ConstAccessor accessor_;
    Vec3LeafSampler sampler_;
};

// A volume's motion lookup for one thread, in place in `slot`; left empty
// when the volume does not move.
inline void emplaceMotion(std::optional<MotionLookup>& slot, const Volume& volume) {
    if (volume.motion) slot.emplace(*volume.motion);
}

// A sparse grid of per-brick bounds (one value per 8^3 voxels, as the
// majorants keep them) raised so that each brick also bounds every brick
// within `radius` bricks (Chebyshev distance): what a lookup advected by up
// to radius x 8 voxels can read. Separable: one pass per axis. Radius 0
// (a volume that does not move) hands `bricks` back as it is.
openvdb::FloatGrid::Ptr dilatedBrickBounds(openvdb::FloatGrid::Ptr bricks, int radius);

// Bricks a lookup advected by `reach` index units can move across.
inline int brickReach(double reach) { return reach > 0 ? int(std::ceil(reach / 8.0)) : 0; }

}  // namespace weft
