#include "core/scene/world_range.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/base/error.hpp"
#include "core/base/options/params.hpp"

namespace weft {

namespace {

// A box never expanded (min above max) holds nothing; a flat one (a single
// triangle) does, though OpenVDB calls it empty.
bool boxWithinWorld(const BBoxd& box) {
    const bool unset = box.min().x() > box.max().x() || box.min().y() > box.max().y() || box.min().z() > box.max().z();
    return unset || (withinWorld(box.min()) && withinWorld(box.max()));
}

void requireWithinWorld(const std::string& what, const Vec3d& p) {
    if (withinWorld(p)) return;
    char text[200];
    std::snprintf(text, sizeof text, " lies at (%g, %g, %g), beyond the +-%g scene units weft renders in", p.x(), p.y(), p.z(), kWorldLimit);
    throw Error(what + text);
}

}  // namespace

bool withinWorld(const Vec3d& p) {
    return std::abs(p.x()) <= kWorldLimit && std::abs(p.y()) <= kWorldLimit && std::abs(p.z()) <= kWorldLimit;
}

void requireSceneWithinWorld(const Scene& scene) {
    const auto boxText = [](const BBoxd& b) {
        char text[240];
        std::snprintf(text, sizeof text, " spans (%g, %g, %g) to (%g, %g, %g), beyond the +-%g scene units weft renders in", b.min().x(),
                      b.min().y(), b.min().z(), b.max().x(), b.max().y(), b.max().z(), kWorldLimit);
        return std::string(text);
    };
    for (std::size_t i = 0; i < scene.volumes.size(); ++i) {
        if (!scene.volumes[i].grid) continue;
        const Vec3d voxel = scene.volumes[i].grid->voxelSize();
        if (!(voxel.x() >= kMinVoxelSize && voxel.y() >= kMinVoxelSize && voxel.z() >= kMinVoxelSize && voxel.x() <= kMaxVoxelSize &&
              voxel.y() <= kMaxVoxelSize && voxel.z() <= kMaxVoxelSize)) {
            char text[200];
            std::snprintf(text, sizeof text, "'): voxel size (%g, %g, %g) as placed is outside [%g, %g] scene units", voxel.x(), voxel.y(),
                          voxel.z(), kMinVoxelSize, kMaxVoxelSize);
            throw Error("volume " + std::to_string(i) + " ('" + scene.volumes[i].source + text);
        }
    }
    for (std::size_t i = 0; i < scene.volumes.size(); ++i)
        if (!boxWithinWorld(scene.volumes[i].worldBox()))
            throw Error("volume " + std::to_string(i) + " ('" + scene.volumes[i].source + "')" + boxText(scene.volumes[i].worldBox()) +
                        " (is its voxel size, scale or translate too large?)");
    for (std::size_t i = 0; i < scene.meshes.size(); ++i)
        if (!boxWithinWorld(scene.meshes[i].bounds()))
            throw Error("mesh " + std::to_string(i) + boxText(scene.meshes[i].bounds()) + " (is a vertex, its scale or translate too large?)");
    requireWithinWorld("the camera's eye", scene.camera.eye);
    requireWithinWorld("the camera's target", scene.camera.target);
    for (const auto& [f, cam] : scene.cameraPath.keys) {
        requireWithinWorld("the camera key at frame " + formatNumber(f) + ": its eye", cam.eye);
        requireWithinWorld("the camera key at frame " + formatNumber(f) + ": its target", cam.target);
    }
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
        if (scene.lights[i].type == LightType::Point) requireWithinWorld("light " + std::to_string(i) + "'s position", scene.lights[i].position);
}

}  // namespace weft
