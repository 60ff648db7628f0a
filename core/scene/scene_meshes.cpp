// The scene's mesh side: merging materials, and the lazily built BVH and
// emitter table (volume-only scenes never pay for them).
#include <mutex>

#include "core/lighting/emitters.hpp"
#include "core/base/error.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "core/scene/scene.hpp"

namespace weft {

struct MeshCache {
    std::once_flag once;
    std::unique_ptr<MeshAccel> accel;
    std::unique_ptr<Emitters> emitters;
};

void Scene::addMesh(TriangleMesh mesh) {
    const auto offset = std::uint32_t(materials.size());
    for (Material& m : mesh.materials) materials.push_back(std::move(m));
    mesh.materials.clear();
    for (std::uint32_t& id : mesh.material) id += offset;
    meshes.push_back(std::move(mesh));
    meshCache_.reset();
    built_.cache.store(nullptr);
}

namespace {

MeshCache& buildCache(const Scene& scene, std::shared_ptr<MeshCache>& slot) {
    static std::mutex slotMutex;  // guards the creation of the slot itself
    std::shared_ptr<MeshCache> cache;
    {
        std::lock_guard<std::mutex> lock(slotMutex);
        if (!slot) slot = std::make_shared<MeshCache>();
        cache = slot;
    }
    std::call_once(cache->once, [&] {
        if (scene.meshes.empty()) throw Error("the scene has no meshes to trace");
        cache->accel = std::make_unique<MeshAccel>(scene.meshes);
        cache->emitters = std::make_unique<Emitters>(scene.meshes, scene.materials);
    });
    return *cache;
}

}  // namespace

const MeshCache& Scene::meshCache() const {
    if (const MeshCache* built = built_.cache.load(std::memory_order_acquire)) return *built;
    const MeshCache& cache = buildCache(*this, meshCache_);
    built_.cache.store(&cache, std::memory_order_release);
    return cache;
}

const MeshAccel& Scene::accel() const { return *meshCache().accel; }
const Emitters& Scene::emitters() const { return *meshCache().emitters; }

}  // namespace weft
