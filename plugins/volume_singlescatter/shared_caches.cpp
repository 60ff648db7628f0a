#include "plugins/volume_singlescatter/shared_caches.hpp"

#include "core/base/shared_cache.hpp"
#include "core/volume/volume_key.hpp"

namespace weft {

namespace {

// Two lights on two overlapping volumes hold eight light caches.
constexpr std::size_t kReachingEntries = 8, kLightCacheEntries = 8;

SharedCache<std::shared_ptr<const VisibleBlocks>>& reachingBlocks() {
    static SharedCache<std::shared_ptr<const VisibleBlocks>> entries(kReachingEntries);
    return entries;
}

SharedCache<openvdb::FloatGrid::ConstPtr>& lightCaches() {
    static SharedCache<openvdb::FloatGrid::ConstPtr> entries(kLightCacheEntries);
    return entries;
}

std::vector<std::shared_ptr<const void>> kept(std::initializer_list<const Volume*> volumes) {
    std::vector<std::shared_ptr<const void>> out;
    for (const Volume* v : volumes)
        if (openvdb::FloatGrid::ConstPtr grid = keptGrid(*v)) out.push_back(grid);
    return out;
}

}  // namespace

std::shared_ptr<const VisibleBlocks> sharedReaching(const Volume& volume, float cutoff, VisibleBlocks::Within within) {
    std::string key = volumeKey(volume) + (within == VisibleBlocks::Within::ActiveBlocks ? "|active" : "|anywhere");
    addKeyNumber(key, cutoff);
    const auto build = [&] { return std::shared_ptr<const VisibleBlocks>(VisibleBlocks::reaching(*volume.grid, cutoff, within)); };
    return reachingBlocks().get(key, build, kept({&volume})).value;
}

SharedLightCache sharedLightCache(const Volume& receiver, const Volume& occluder, const VisibleBlocks* occluderReaching,
                                  const DirectionalOrPointLight& light, const LightCacheSettings& s) {
    std::string key = volumeKey(receiver) + "|lit by|" + volumeKey(occluder) + (light.isPoint ? "|point" : "|directional");
    for (int a = 0; a < 3; ++a) addKeyNumber(key, light.isPoint ? light.position[a] : light.toLight[a]);
    for (const double v : {s.step, s.gain, s.cutoff, s.sigmaMin, double(s.coarsening)}) addKeyNumber(key, v);
    const auto build = [&] {
        return openvdb::FloatGrid::ConstPtr(buildLightCache(receiver, occluder, occluderReaching, light, s));
    };
    auto found = lightCaches().get(key, build, kept({&receiver, &occluder}));
    return {std::move(found.value), found.reused};
}

void clearScatterCaches() {
    reachingBlocks().clear();
    lightCaches().clear();
}

}  // namespace weft
