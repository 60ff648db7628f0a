#pragma once
// What volume.singlescatter derives from a volume that a frame sequence of
// a still volume, a sweep or a Python session renders again and again: the
// blocks its marches leap by and its light caches. Kept process-wide by the
// volume's key (core/volume/volume_key.hpp: an unchanged file's fresh load
// finds them) through core/base/shared_cache.hpp; the stats count the light
// caches built and reused.
#include <memory>

#include "core/volume/skip/visible_blocks.hpp"
#include "plugins/volume_singlescatter/light_cache.hpp"

namespace weft {

// VisibleBlocks::reaching of the volume's density (null where it is).
std::shared_ptr<const VisibleBlocks> sharedReaching(const Volume& volume, float cutoff, VisibleBlocks::Within within);

struct SharedLightCache {
    openvdb::FloatGrid::ConstPtr grid;
    bool reused = false;
};
// buildLightCache's grid for these volumes, light and settings.
SharedLightCache sharedLightCache(const Volume& receiver, const Volume& occluder, const VisibleBlocks* occluderReaching,
                                  const DirectionalOrPointLight& light, const LightCacheSettings& settings);

void clearScatterCaches();

}  // namespace weft
