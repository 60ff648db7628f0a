#include "plugins/volume_singlescatter/scatter_params.hpp"

#include <cmath>
#include <sstream>

#include "core/base/error.hpp"
#include "core/lighting/emitters.hpp"

namespace weft {

namespace {

const std::vector<std::string> kCameraKeys = {"translate", "rotate", "lookat", "up", "fov",
                                              "aperture", "focal", "znear", "zfar"};

std::function<void(const std::string&)> listCheck(std::size_t minCount, std::size_t maxCount) {
    return [=](const std::string& text) { parseNumberList(text, "", minCount, maxCount); };
}

Vec3d vec3(const ParamSet& p, const std::string& key) {
    const std::vector<double> v = parseNumberList(p.getString(key), key, 3, 3);
    return Vec3d(v[0], v[1], v[2]);
}

// vdb_render's camera: rotations about X, Y then Z (degrees) and a
// translation, or look-at (default: the active box centre); horizontal
// field of view from aperture and focal length.
Camera vdbRenderCamera(const ParamSet& p, const Scene& scene, double aspect) {
    if (p.wasSet("rotate") && p.wasSet("lookat")) throw Error("volume.singlescatter: set rotate or lookat, not both (as vdb_render)");
    if (p.wasSet("fov") && p.wasSet("focal")) throw Error("volume.singlescatter: set fov or focal, not both (as vdb_render)");
    const double aperture = p.getFloat("aperture");
    double focal = p.getFloat("focal");
    if (p.wasSet("fov")) focal = aperture / (2.0 * std::tan(p.getFloat("fov") * M_PI / 360.0));
    Camera cam;
    cam.eye = vec3(p, "translate");
    cam.fovY = 2.0 * std::atan(0.5 * aperture / focal / aspect) * 180.0 / M_PI;
    if (p.wasSet("rotate")) {
        const Vec3d r = vec3(p, "rotate") * (M_PI / 180.0);
        openvdb::math::Mat3d m = openvdb::math::rotation<openvdb::math::Mat3d>(openvdb::math::X_AXIS, r[0]);
        m = m * openvdb::math::rotation<openvdb::math::Mat3d>(openvdb::math::Y_AXIS, r[1]);
        m = m * openvdb::math::rotation<openvdb::math::Mat3d>(openvdb::math::Z_AXIS, r[2]);
        cam.target = cam.eye + m.transpose() * Vec3d(0, 0, -1);  // row-vector convention, as OpenVDB maps
        cam.up = m.transpose() * Vec3d(0, 1, 0);
        return cam;
    }
    cam.up = vec3(p, "up");
    if (p.wasSet("lookat")) cam.target = vec3(p, "lookat");
    else {
        if (scene.volumes.empty()) throw Error("volume.singlescatter: compat=vdb_render needs lookat or rotate in a scene without volumes");
        const Volume& v = scene.volumes.front();
        cam.target = v.grid->transform().indexToWorld(v.grid->evalActiveVoxelBoundingBox().getCenter());
    }
    return cam;
}

DirectionalOrPointLight paramLight(const ParamSet& p) {
    const std::vector<double> v = parseNumberList(p.getString("light"), "light", 3, 6);
    DirectionalOrPointLight l;
    l.toLight = Vec3d(v[0], v[1], v[2]);
    if (l.toLight.length() < 1e-12) throw Error("volume.singlescatter: light direction must not be zero");
    l.toLight.normalize();
    l.color = v.size() == 6 ? Vec3d(v[3], v[4], v[5]) : Vec3d(0.7);
    return l;
}

std::vector<DirectionalOrPointLight> sceneLights(const Scene& scene) {
    std::vector<DirectionalOrPointLight> lights;
    for (const Light& s : scene.lights) {
        if (s.type == LightType::Environment)
            throw Error("volume.singlescatter: environment lights are not supported yet (directional, point and emissive triangles are)");
        DirectionalOrPointLight l;
        l.isPoint = s.type == LightType::Point;
        l.toLight = -s.direction;
        l.position = s.position;
        l.color = Vec3d(s.color[0], s.color[1], s.color[2]) * s.intensity;
        lights.push_back(l);
    }
    return lights;
}

}  // namespace

std::vector<double> parseNumberList(const std::string& text, const std::string& key, std::size_t minCount,
                                    std::size_t maxCount) {
    std::vector<double> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        std::size_t used = 0;
        double v = 0;
        try {
            v = std::stod(item, &used);
        } catch (...) {
            used = 0;
        }
        if (used == 0 || used != item.size() || !std::isfinite(v)) out.clear(), out.resize(maxCount + 1);
        else out.push_back(v);
    }
    if (out.size() < minCount || out.size() > maxCount) {
        const std::string what = minCount == maxCount ? std::to_string(minCount) : std::to_string(minCount) + " or " + std::to_string(maxCount);
        throw Error((key.empty() ? "" : key + ": ") + "expected " + what + " comma-separated finite numbers, got '" + text + "'");
    }
    return out;
}

std::vector<ParamSpec> scatterParamSpecs() {
    return {
        enumParam("compat", "none", {"none", "vdb_render"}, "vdb_render: accept its camera options and build its camera"),
        stringParam("absorb", "0.1,0.1,0.1", "absorption coefficients R,G,B per voxel length per unit density (set: wins over the scene's media)", listCheck(3, 3)),
        stringParam("scatter", "1.5,1.5,1.5", "scattering coefficients R,G,B per voxel length per unit density (set: wins over the scene's media)", listCheck(3, 3)),
        stringParam("light", "0.3,0.3,0,0.7,0.7,0.7", "directional light X,Y,Z towards the light [,R,G,B] (scene lights win unless set)", listCheck(3, 6)),
        floatParam("gain", 0.2, 0, 1e3, "scatter along the shadow ray: extinction there divided by 1 + gain * distance"),
        floatParam("cutoff", 0.005, 0, 1, "densities below it are empty; rays stop once |T|^2 falls below it"),
        floatParam("step", 1, 1e-3, 64, "primary-ray step in voxel lengths (cube root of a voxel's volume) of the finest volume crossed"),
        floatParam("shadowstep", 3, 1e-3, 64, "shadow-ray step in voxel lengths of the volume crossed (raymarch and the cache)"),
        enumParam("estimator", "cached", {"cached", "ratio", "raymarch"},
                  "shadow transmittance: cached grid, ratio tracking (unbiased), or vdb_render's march"),
        intParam("cache_voxel", 2, 1, 16, "light cache voxel size, in density voxels (estimator=cached)"),
        boolParam("jitter", true, "per-pixel random offset of primary samples (no rings; raymarch keeps vdb_render's phase)"),
        enumParam("phase", "isotropic", {"isotropic", "hg"}, "phase function (isotropic is vdb_render's; hg: Henyey-Greenstein)"),
        floatParam("g", 0, -0.99, 0.99, "Henyey-Greenstein anisotropy"),
        boolParam("physical", false, "mesh.pathtrace's conventions: phase functions normalised over the sphere (isotropic 1/4pi), gain 0; false: vdb_render's isotropic phase of 1"),
        stringParam("translate", "0,0,0", "vdb_render camera translation (compat only)", listCheck(3, 3)),
        stringParam("rotate", "0,0,0", "vdb_render camera rotation X,Y,Z degrees (compat only)", listCheck(3, 3)),
        stringParam("lookat", "0,0,0", "vdb_render look-at target (compat only; default: active box centre)", listCheck(3, 3)),
        stringParam("up", "0,1,0", "vdb_render up vector with lookat (compat only)", listCheck(3, 3)),
        floatParam("fov", 44.8, 1e-3, 179, "vdb_render horizontal field of view, degrees (compat only)"),
        floatParam("aperture", 41.2136, 1e-3, 1e4, "vdb_render camera aperture, mm (compat only)"),
        floatParam("focal", 50, 1e-3, 1e4, "vdb_render focal length, mm (compat only)"),
        floatParam("znear", 1e-3, 0, 1e30, "vdb_render near plane (compat only)"),
        floatParam("zfar", 3.4e38, 0, 3.5e38, "vdb_render far plane (compat only)"),
    };
}

ScatterParams readScatterParams(const ParamSet& p, const Scene& scene, double aspect) {
    ScatterParams s;
    s.vdbRenderCompat = p.getString("compat") == "vdb_render";
    if (!s.vdbRenderCompat)
        for (const std::string& key : kCameraKeys)
            if (p.wasSet(key))
                throw Error("volume.singlescatter: '" + key + "' is a vdb_render camera option; add --set compat=vdb_render");
    s.absorb = vec3(p, "absorb");
    s.scatter = vec3(p, "scatter");
    for (int c = 0; c < 3; ++c)
        if (s.absorb[c] < 0 || s.scatter[c] < 0) throw Error("volume.singlescatter: absorb and scatter must not be negative");
    s.physical = p.getBool("physical");
    if (s.physical && s.vdbRenderCompat) throw Error("volume.singlescatter: physical=true and compat=vdb_render exclude each other (vdb_render's phase is not normalised)");
    if (s.physical && p.wasSet("gain") && p.getFloat("gain") != 0)
        throw Error("volume.singlescatter: gain is vdb_render's non-physical shadow scatter; physical=true needs gain=0");
    s.phaseScale = s.physical ? 1.0 / (4.0 * M_PI) : 1.0;
    s.gain = s.physical ? 0.0 : p.getFloat("gain");
    s.cutoff = p.getFloat("cutoff");
    s.step = p.getFloat("step");
    s.shadowStep = p.getFloat("shadowstep");
    s.cacheCoarsening = int(p.getInt("cache_voxel"));
    const std::string& e = p.getString("estimator");
    s.estimator = e == "raymarch" ? ShadowEstimator::Raymarch : e == "ratio" ? ShadowEstimator::Ratio : ShadowEstimator::Cached;
    s.jitter = p.getBool("jitter") && s.estimator != ShadowEstimator::Raymarch;
    s.phase = p.getString("phase") == "hg" ? Phase::HenyeyGreenstein : Phase::Isotropic;
    s.g = p.getFloat("g");
    // Emissive triangles are the scene's lights too; the `light` default
    // stands in only where the scene has no light at all.
    s.emitters = !s.vdbRenderCompat && !scene.meshes.empty() && !scene.emitters().empty();
    if (s.vdbRenderCompat || p.wasSet("light") || (scene.lights.empty() && !s.emitters)) s.lights = {paramLight(p)};
    else s.lights = sceneLights(scene);
    if (s.vdbRenderCompat) s.camera = vdbRenderCamera(p, scene, aspect);
    return s;
}

}  // namespace weft
