#pragma once
// A technique is a render operation registered by name: a parameter table,
// a one-line summary, and a factory that validates parameters against the
// scene at construction and returns an object whose render() makes the image.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "core/base/options/params.hpp"
#include "core/base/registry.hpp"
#include "core/base/run/render_context.hpp"
#include "core/scene/scene.hpp"

namespace weft {

class Technique {
public:
    virtual ~Technique() = default;
    // Renders RGBA (premultiplied, scene-linear) plus any AOVs it produces.
    virtual Image render(const Scene& scene, RenderContext& ctx) = 0;
};

// What a technique renders. A scene holding content the technique cannot
// render is refused with the techniques that can, never half rendered.
enum class Content : unsigned { None = 0, Volumes = 1, Meshes = 2, VolumesAndMeshes = 3 };
constexpr bool covers(Content has, Content needs) { return (unsigned(has) & unsigned(needs)) == unsigned(needs); }
const char* contentName(Content c);  // "volumes", "meshes", "volumes and meshes", "no scene content"

struct ConvergedReference {
    std::string technique;
    std::vector<std::string> sets;  // "key=value"
    int spp = 1;
};

struct TradeKnob {
    std::string key;
    std::vector<std::string> values;
};

struct TechniqueInfo {
    std::string name;
    std::string summary;
    ParamTable params;
    std::function<std::unique_ptr<Technique>(const Scene&, const ParamSet&)> create;
    // Whether each camera sample takes its own time in the shutter
    // (Scene::cameraAt); others cannot render a moving camera.
    bool motionBlur = false;
    Content renders = Content::Volumes;
    // Peak working memory per pixel (image, accumulators, AOVs, G-buffers,
    // pyramids), measured as the slope of peak RSS between 1024x1024 and
    // 2048x2048 renders; the host refuses renders above --max-memory before
    // they start. 32: an RGBA float image and its accumulator.
    double bytesPerPixel = 32;
    // The converged render this technique's images are measured against
    // (weft sweep/tune --reference auto): a technique (itself, or the one
    // its family converges to) with the parameters and samples per pixel
    // that converge it. No technique: the family has no reference.
    ConvergedReference reference;
    // Its speed/accuracy knobs (weft tune): a key (a parameter, or spp) and
    // a coarse grid of values, cheapest first.
    std::vector<TradeKnob> knobs;
    // Whether it scatters light in volumes, reading their colour grids
    // (Volume::color); the host refuses a colour grid a scene names for
    // the others.
    bool scatters = false;
    // Whether it blurs volumes that move by their velocity grids
    // (Volume::motion) though its camera renders one instant; motionBlur
    // techniques blur both. The host refuses moving volumes to the others.
    bool velocityBlur = false;
    // Whether it renders volume emission (Volume::emission); the host
    // refuses emitting volumes to the others.
    bool emission = false;
};

// The registered techniques for which `has` holds, as "a, b or c" (the
// alternatives a refusal names).
std::string techniquesWith(const std::function<bool(const TechniqueInfo&)>& has);

// Throws when the scene holds volumes or meshes the technique does not
// render, naming what would be dropped and the techniques that render it all.
void checkTechniqueContent(const TechniqueInfo& info, const Scene& scene);

using TechniqueRegistry = NamedRegistry<TechniqueInfo>;
TechniqueRegistry& techniques();

// Registers a built-in technique from its own .cpp file:
//   static TechniqueRegistrar reg{{"volume.raymarch", "...", table, factory}};
struct TechniqueRegistrar {
    explicit TechniqueRegistrar(TechniqueInfo info) { techniques().add(std::move(info)); }
};

}  // namespace weft
