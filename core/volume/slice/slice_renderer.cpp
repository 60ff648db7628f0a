#include "core/volume/slice/slice_renderer.hpp"

#include "core/base/error.hpp"

namespace weft {

std::vector<ParamSpec> sliceParamSpecs() {
    return {floatParam("spacing", 1.0, 1.0 / 64, 64, "distance between slices, in voxels (the minimum sampling distance)"),
            intParam("table_res", 256, 8, 2048, "pre-integration table entries per scalar axis"),
            enumParam("table_precision", "float32", {"float32", "8bit"}, "pre-integration table storage (8bit emulates RGBA8 tables)")};
}

SliceParams readSliceParams(const ParamSet& p) {
    return {p.getFloat("spacing"), int(p.getInt("table_res")),
            p.getString("table_precision") == "8bit" ? PreintPrecision::Bits8 : PreintPrecision::Float32};
}

const Volume& requireSliceableVolume(const Scene& scene, const std::string& technique) {
    if (scene.volumes.empty()) throw Error(technique + " renders volumes; the scene has none");
    for (std::size_t k = 0; k < scene.volumes.size(); ++k) {
        const Volume& vol = scene.volumes[k];
        if (vol.tf.lookup(vol.grid->background()).extinction > 0)
            throw Error(technique + ": the transfer function" + (scene.volumes.size() > 1 ? " of volume " + std::to_string(k) : "") +
                        " must be transparent at the grid's background value");
    }
    return scene.volumes.front();
}

}  // namespace weft
