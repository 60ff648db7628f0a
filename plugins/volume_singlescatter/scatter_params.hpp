#pragma once
// Parameters of volume.singlescatter, named as vdb_render names them so a
// vdb_render user can switch without relearning. With compat=vdb_render the
// camera options (translate, rotate, lookat, up, fov, aperture, focal,
// znear, zfar) are accepted too and the camera is built exactly as
// vdb_render builds it; otherwise the scene's camera is used.
#include <optional>
#include <string>
#include <vector>

#include "core/scene/camera.hpp"
#include "core/base/options/params.hpp"
#include "core/scene/scene.hpp"

namespace weft {

enum class ShadowEstimator { Raymarch, Ratio, Cached };
enum class Phase { Isotropic, HenyeyGreenstein };

struct DirectionalOrPointLight {
    bool isPoint = false;
    Vec3d toLight;   // directional: unit direction towards the light
    Vec3d position;  // point: world position
    Vec3d color;     // radiance scale (colour x intensity)
};

struct ScatterParams {
    Vec3d absorb, scatter;  // coefficients per voxel length per unit density
    double gain = 0.2;      // vdb_render's "scatter along the shadow ray"
    double cutoff = 0.005;  // density and transmittance cutoff
    double step = 1, shadowStep = 3;
    int cacheCoarsening = 2;  // light cache voxels per density voxel, per axis
    ShadowEstimator estimator = ShadowEstimator::Cached;
    bool jitter = true;     // per-pixel offset of the primary samples
    Phase phase = Phase::Isotropic;
    double g = 0;
    bool vdbRenderCompat = false;
    // The path tracer's conventions: phase functions integrate to 1 over the
    // sphere (isotropic 1/4pi) and gain is 0. Off: vdb_render's phase of 1.
    bool physical = false;
    double phaseScale = 1.0;  // 1 / (4 pi) when physical
    bool emitters = false;    // emissive triangles light the scene too (not in compat mode)
    std::vector<DirectionalOrPointLight> lights;
    std::optional<Camera> camera;  // set in vdb_render compatibility mode
};

std::vector<ParamSpec> scatterParamSpecs();

// Reads the parameters against the scene (its lights and camera; in
// compatibility mode the grid's active box centre is vdb_render's default
// target). Errors name the key and what was wrong.
ScatterParams readScatterParams(const ParamSet& p, const Scene& scene, double aspect);

// "x,y,z" (or n comma-separated numbers) -> numbers; a clear error otherwise.
std::vector<double> parseNumberList(const std::string& text, const std::string& key, std::size_t minCount,
                                    std::size_t maxCount);

}  // namespace weft
