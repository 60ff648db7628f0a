#pragma once
// The scene: camera, volumes, lights, and the render settings a scene file
// may carry (technique, parameters, resolution), which the command line can
// override. Only what the scene uses is built.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/volume.hpp"

namespace weft {

enum class LightType { Directional, Point, Environment };

struct Light {
    LightType type = LightType::Directional;
    Vec3d direction{0, -1, 0};  // directional: the way light travels
    Vec3d position{0, 0, 0};    // point
    Vec3f color{1, 1, 1};
    double intensity = 1.0;
};

struct SceneRenderSettings {
    std::optional<std::string> technique;
    std::map<std::string, std::string> params;  // key -> value text
    std::optional<int> width, height, spp;
    std::optional<std::uint64_t> seed;
};

struct Scene {
    std::string source;  // what was loaded: a path or builtin:NAME
    Camera camera;
    std::vector<Volume> volumes;
    std::vector<Light> lights;
    SceneRenderSettings render;

    BBoxd worldBox() const;
};

// Loads a scene from a .json file, a bare .vdb (framed like vdb_render does,
// default transfer function over the grid's value range) or builtin:NAME.
// aspect is width/height of the image, used to frame scenes without a camera;
// when not given, a scene file's own resolution decides, else 1.
// gridName picks the grid of a bare .vdb (default: "density", else the first float grid).
// frame, when given, selects what varies with the frame in a scene file:
// frame-numbered volume files ("smoke.#.vdb", see core/frames.hpp) and a
// camera keyed by frame ("camera": {"keys": [{"frame": 1, "eye": ...}, ...]}).
Scene loadScene(const std::string& input, std::optional<double> aspect = std::nullopt, const std::string& gridName = "",
                std::optional<int> frame = std::nullopt);

// Names of the built-in scenes, "cloud|sphere".
const char* builtinSceneNames();

}  // namespace weft
