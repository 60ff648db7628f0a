#pragma once
// The ranges a scene must stay in (core/base/world_limit.hpp), checked once
// the scene has loaded and, for placements, as they are read.
#include "core/base/world_limit.hpp"
#include "core/scene/scene.hpp"

namespace weft {

// Whether each coordinate lies within +-kWorldLimit.
bool withinWorld(const Vec3d& p);

// Throws one line naming the first item beyond the ranges: a volume's voxel
// size or box, a mesh's box, the camera's eye or target (each key's too), a
// point light.
void requireSceneWithinWorld(const Scene& scene);

}  // namespace weft
