#include "plugins/volume_singlescatter/scatter_volume.hpp"

#include <algorithm>
#include <cmath>

namespace weft {

namespace {

void setCoefficients(ScatterVolume& v, const Vec3d& absorb, const Vec3d& scatter) {
    v.sigmaT = absorb + scatter;
    for (int c = 0; c < 3; ++c) v.albedo[c] = v.sigmaT[c] > 0 ? scatter[c] / v.sigmaT[c] : 0.0;
}

}  // namespace

std::vector<ScatterVolume> scatterVolumes(const Scene& scene, const ScatterParams& params, bool paramsWin) {
    std::vector<ScatterVolume> out;
    for (const Volume& vol : scene.volumes) {
        if (vol.empty()) continue;  // OpenVDB's intersector refuses empty grids; they add nothing
        ScatterVolume v;
        v.volume = &vol;
        v.indexGrid = occupancyIndexGrid(vol);
        v.intersector = std::make_shared<const VdbIntersector>(*v.indexGrid);
        v.phase = params.phase, v.g = params.g;
        if (vol.medium.fromScene && !paramsWin) {
            setCoefficients(v, vol.medium.absorb, vol.medium.scatter);
            if (vol.medium.g != 0) v.phase = Phase::HenyeyGreenstein, v.g = vol.medium.g;
        } else {
            setCoefficients(v, params.absorb, params.scatter);
        }
        v.majorantDensity = std::max(std::abs(vol.valueMin), std::abs(vol.valueMax));
        v.voxelLength = vol.voxelLength();
        v.uniform = vol.grid->transform().hasUniformScale();
        v.map = vol.grid->transform().baseMap().get();
        out.push_back(std::move(v));
    }
    return out;
}

}  // namespace weft
