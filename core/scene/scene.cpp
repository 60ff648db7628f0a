// What the scene answers about itself (its box, its camera at a shutter
// time, whether anything moves) and the checks a technique makes of it.
#include "core/scene/scene.hpp"

#include "core/base/error.hpp"

namespace weft {

bool Scene::volumesMove() const {
    for (const Volume& v : volumes)
        if (v.motion) return true;
    return false;
}

void requireStillVolumes(const Scene& scene, const std::string& technique, const std::string& alternatives) {
    for (const Volume& v : scene.volumes)
        if (v.motion)
            throw Error(technique + " does not blur volumes by their velocity; volume '" + v.source + "' moves (" + v.grids +
                        ") while the shutter is open: render it with " + alternatives + ", or close the shutter (camera.shutter [0, 0])");
}

void requireNoColorGrids(const Scene& scene, const std::string& technique, const std::string& alternatives) {
    for (const Volume& v : scene.volumes)
        if (v.color && !v.gridsPicked)
            throw Error(technique + " does not scatter light, so it would not use the colour grid of volume '" + v.source + "' (" + v.grids +
                        "): render it with " + alternatives + ", or leave the colour out of 'grids'");
}

std::string unusedColorGrids(const Scene& scene, const std::string& technique) {
    std::string sources;
    for (const Volume& v : scene.volumes)
        if (v.color) sources += (sources.empty() ? "'" : ", '") + v.source + "'";
    if (sources.empty()) return "";
    return technique + " does not scatter light: the colour grid of " + sources + " is not used";
}

void requireNoEmission(const Scene& scene, const std::string& technique, const std::string& alternatives) {
    for (const Volume& v : scene.volumes)
        if (v.emission)
            throw Error(technique + " does not render volume emission; volume '" + v.source + "' emits (" + v.grids +
                        "): render it with " + alternatives);
}

Camera Scene::cameraAt(double u) const {
    return cameraPath.keys.size() < 2 || shutter.instant() ? camera : cameraPath.at(shutter.frameTime(frame, u));
}

std::optional<CameraRays> Scene::stillCameraRays(int width, int height) const {
    if (cameraMoves()) return std::nullopt;
    return CameraRays(cameraAt(0), width, height);
}

bool Scene::cameraMoves() const {
    if (cameraPath.keys.size() < 2 || shutter.instant()) return false;
    const double open = shutter.frameTime(frame, 0), close = shutter.frameTime(frame, 1);
    const auto differs = [](const Camera& a, const Camera& b) {
        return a.eye != b.eye || a.target != b.target || a.up != b.up || a.fovY != b.fovY;
    };
    const Camera first = cameraPath.at(open);
    if (differs(first, cameraPath.at(close))) return true;
    for (const auto& [f, cam] : cameraPath.keys)  // a path may leave and come back within the shutter
        if (f > open && f < close && differs(first, cam)) return true;
    return false;
}

BBoxd Scene::worldBox() const {
    BBoxd box;
    for (const Volume& v : volumes) box.expand(v.worldBox());
    for (const TriangleMesh& m : meshes) box.expand(m.bounds());
    return box;
}

}  // namespace weft
