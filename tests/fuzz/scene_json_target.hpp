#pragma once
// Fuzz target: scene files (core/scene/scene_loader.cpp) and what `weft
// render` does with a loaded scene before rendering: the precedence of the
// render block and the check of its parameters against the technique.
// Scenes may name the small files written beside them (fuzz.vdb, fuzz.obj,
// fuzz.ply; tests/fuzz/scene.dict lists them with every key).
#include <openvdb/io/File.h>

#include <nlohmann/json.hpp>

#include <map>

#include "core/base/options/render_options.hpp"
#include "core/scene/scene.hpp"
#include "plugins/host/command.hpp"
#include "plugins/technique.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace weft::fuzz {

inline void writeSceneNeighbours() {
    static const bool written = [] {
        initVdb();
        auto grid = makeProceduralGrid("sphere", 8, 1);
        grid->setName("density");
        openvdb::io::File file((scratchDir() / "fuzz.vdb").string());
        file.write({grid});
        file.close();
        writeScratch("fuzz.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n");
        writeScratch("fuzz.ply",
                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        return true;
    }();
    (void)written;
}

// Legitimate scenes whose cost grows without bound with one number (a
// 1024^3 procedural grid, subdivision level 8) are slow, not wrong: they
// are left out so a run measures robustness, not patience.
inline bool tooSlowToFuzz(const nlohmann::json& scene) {
    if (!scene.is_object()) return false;
    const auto above = [](const nlohmann::json& list, const char* key, double limit) {
        if (!list.is_array()) return false;
        for (const auto& item : list)
            if (item.is_object() && item.contains(key) && item[key].is_number() && item[key].get<double>() > limit) return true;
        return false;
    };
    return (scene.contains("volumes") && above(scene["volumes"], "resolution", 24)) ||
           (scene.contains("meshes") && above(scene["meshes"], "subdivision", 2));
}

inline Outcome sceneJson(const std::uint8_t* data, std::size_t size) {
    const std::string_view text = asText(data, size);
    if (tooSlowToFuzz(nlohmann::json::parse(text.begin(), text.end(), nullptr, false))) return {false, "", true};
    writeSceneNeighbours();
    const std::string path = writeScratch("scene.json", text);
    return guarded([&] {
        const Scene scene = loadScene(path);
        const EffectiveRender q = effectiveRender(SceneRender{}, scene.render);
        requireValid(q.resolution);
        const TechniqueInfo& info = techniques().get(q.technique);
        std::map<std::string, std::string> given;
        for (const std::string& kv : q.sets) {
            auto [k, v] = splitKeyValue(kv, "set");
            given[k] = v;
        }
        info.params.parse(given);
        checkTechniqueContent(info, scene);
    });
}

}  // namespace weft::fuzz
