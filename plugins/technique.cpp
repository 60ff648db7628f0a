#include "plugins/technique.hpp"

namespace weft {

TechniqueRegistry& techniques() {
    static TechniqueRegistry registry("technique");
    return registry;
}

const char* contentName(Content c) {
    switch (c) {
        case Content::Volumes: return "volumes";
        case Content::Meshes: return "meshes";
        case Content::VolumesAndMeshes: return "volumes and meshes";
        case Content::None: break;
    }
    return "no scene content";
}

std::string techniquesWith(const std::function<bool(const TechniqueInfo&)>& has) {
    std::vector<std::string> names;
    for (const TechniqueInfo* t : techniques().all())
        if (has(*t)) names.push_back(t->name);
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i) list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return list.empty() ? "no technique" : list;
}

void checkTechniqueContent(const TechniqueInfo& info, const Scene& scene) {
    const Content needs = Content((scene.volumes.empty() ? 0u : 1u) | (scene.meshes.empty() ? 0u : 2u));
    if (covers(info.renders, needs)) return;
    std::string dropped;
    if (!scene.volumes.empty() && !covers(info.renders, Content::Volumes))
        dropped = std::to_string(scene.volumes.size()) + (scene.volumes.size() == 1 ? " volume" : " volumes");
    if (!scene.meshes.empty() && !covers(info.renders, Content::Meshes))
        dropped += (dropped.empty() ? "" : " and ") + std::to_string(scene.meshes.size()) + (scene.meshes.size() == 1 ? " mesh" : " meshes");
    std::string able;
    for (const TechniqueInfo* t : techniques().all())
        if (covers(t->renders, needs)) able += (able.empty() ? "" : ", ") + t->name;
    throw Error(info.name + " renders " + contentName(info.renders) + ", and the scene '" + scene.source + "' also has " +
                dropped + " it would drop; " +
                (able.empty() ? std::string("no technique renders ") + contentName(needs) + " together yet"
                              : "use one that renders " + std::string(contentName(needs)) + ": " + able));
}

}  // namespace weft
