#pragma once
// The scene: camera, volumes, lights, and the render settings a scene file
// may carry (technique, parameters, resolution), which the command line can
// override. Only what the scene uses is built.
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/base/options/scene_render.hpp"
#include "core/scene/camera.hpp"
#include "core/mesh/mesh.hpp"
#include "core/volume/volume.hpp"

namespace weft {

enum class LightType { Directional, Point, Environment };

struct Light {
    LightType type = LightType::Directional;
    Vec3d direction{0, -1, 0};  // directional: the way light travels
    Vec3d position{0, 0, 0};    // point
    Vec3f color{1, 1, 1};
    double intensity = 1.0;
};

class MeshAccel;
class Emitters;
struct MeshCache;

struct Scene {
    std::string source;  // what was loaded: a path or builtin:NAME
    Camera camera;           // at the frame rendered
    CameraPath cameraPath;   // keyed cameras; empty when the camera is fixed
    Shutter shutter;         // instant unless the scene opens it
    double frame = 0;        // the frame rendered (the first key's without --frames)
    std::vector<Volume> volumes;
    std::vector<TriangleMesh> meshes;  // material ids index `materials`
    std::vector<Material> materials;
    std::vector<Light> lights;
    SceneRender render;  // the file's "render" block (read through core/base/options/render_options.hpp); the command line wins

    BBoxd worldBox() const;
    // The camera at shutter time u in [0, 1): `camera` unless it moves.
    Camera cameraAt(double u) const;
    // Whether the camera moves while the shutter is open (motion blur).
    bool cameraMoves() const;
    // The ray frame of a width x height render, built once, where the camera
    // holds still all frame long; none where it moves (rays then come from
    // cameraAt(time)).
    std::optional<CameraRays> stillCameraRays(int width, int height) const;
    // Whether a volume moves by its velocity while the shutter is open.
    bool volumesMove() const;
    // Adds a mesh, moving its materials into the scene's table.
    void addMesh(TriangleMesh mesh);
    // The Embree BVH over every mesh and the emissive triangles, built on the
    // first call (thread-safe). Meshes must not change after that.
    const MeshAccel& accel() const;
    const Emitters& emitters() const;

private:
    // The built cache, read without a lock on every call after the first:
    // rays ask for the BVH and the emitters millions of times, and a mutex
    // and a shared_ptr copy per call serialised them. A copy of the scene
    // starts empty and finds the shared cache on its first call.
    struct BuiltMeshCache {
        std::atomic<const MeshCache*> cache{nullptr};
        BuiltMeshCache() = default;
        BuiltMeshCache(const BuiltMeshCache&) {}
        BuiltMeshCache& operator=(const BuiltMeshCache&) {
            cache.store(nullptr);
            return *this;
        }
    };
    const MeshCache& meshCache() const;

    mutable std::shared_ptr<MeshCache> meshCache_;
    mutable BuiltMeshCache built_;
};

// For techniques that do not render volume emission: an Error naming the
// first emitting volume and `alternatives`, the techniques that do.
void requireNoEmission(const Scene& scene, const std::string& technique, const std::string& alternatives);
// For techniques that render one instant of a volume: an Error naming the
// first volume that moves by its velocity while the shutter is open, and
// `alternatives`, the techniques that blur it.
void requireStillVolumes(const Scene& scene, const std::string& technique, const std::string& alternatives);
// For techniques that do not scatter light in volumes (a colour grid tints
// the scattering only): an Error naming the first volume whose colour grid
// the scene file names. A bare .vdb's colour, found by its conventional
// name, is not an error: unusedColorGrids says it in one line instead.
void requireNoColorGrids(const Scene& scene, const std::string& technique, const std::string& alternatives);
// "" or one line naming the volumes whose colour grid the technique leaves unused.
std::string unusedColorGrids(const Scene& scene, const std::string& technique);

// Loads a scene from a .json file, a bare .obj/.ply mesh (framed like a bare
// .vdb, lit by its emissive materials or else by a light over the camera), a bare .vdb (framed like vdb_render does,
// default transfer function over the grid's value range) or builtin:NAME.
// aspect is width/height of the image, used to frame scenes without a camera;
// when not given, a scene file's own resolution decides, else 1.
// gridName picks the grid of a bare .vdb (default: "density", else the first float grid).
// frame, when given, selects what varies with the frame in a scene file:
// frame-numbered volume files ("smoke.#.vdb", see core/base/options/frames.hpp) and a
// camera keyed by frame ("camera": {"keys": [{"frame": 1, "eye": ...}, ...]}),
// which, with an open shutter ("camera": {"shutter": [-0.25, 0.25]}), moves
// within the frame: motion blur whose time samples follow the frame.
Scene loadScene(const std::string& input, std::optional<double> aspect = std::nullopt, const std::string& gridName = "",
                std::optional<int> frame = std::nullopt);

// Names of the built-in scenes, "cloud|sphere".
const char* builtinSceneNames();

}  // namespace weft
