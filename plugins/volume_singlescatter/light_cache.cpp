#include "plugins/volume_singlescatter/light_cache.hpp"

#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/Morphology.h>
#include <openvdb/tree/LeafManager.h>

#include <cmath>

namespace weft {

namespace {

using Sampler = openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>;

int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Every cache voxel a trilinear lookup of a non-empty point can reach; the
// cache's voxels are `factor` density voxels wide, centred on a density voxel.
openvdb::FloatGrid::Ptr cacheTopology(const openvdb::FloatGrid& density, int factor) {
    openvdb::FloatGrid::Ptr cache = openvdb::FloatGrid::create(0.0f);
    openvdb::math::Transform::Ptr xf = density.transform().copy();
    xf->preScale(double(factor));
    cache->setTransform(xf);
    if (factor == 1) {
        cache->tree().topologyUnion(density.tree());
        cache->tree().voxelizeActiveTiles();
    } else {
        auto acc = cache->getAccessor();
        for (auto it = density.tree().cbeginValueOn(); it; ++it) {
            const openvdb::CoordBBox box = it.getBoundingBox();
            for (int x = floorDiv(box.min().x(), factor); x <= floorDiv(box.max().x(), factor); ++x)
                for (int y = floorDiv(box.min().y(), factor); y <= floorDiv(box.max().y(), factor); ++y)
                    for (int z = floorDiv(box.min().z(), factor); z <= floorDiv(box.max().z(), factor); ++z)
                        acc.setValueOn(openvdb::Coord(x, y, z));
        }
    }
    openvdb::tools::dilateActiveValues(cache->tree(), 1, openvdb::tools::NN_FACE_EDGE_VERTEX,
                                       openvdb::tools::EXPAND_TILES);
    return cache;
}

class PathMarcher {
public:
    PathMarcher(const Volume& volume, const DirectionalOrPointLight& light, const LightCacheSettings& s)
        : volume_(volume), light_(light), s_(s), acc_(volume.grid->getConstAccessor()),
          sampler_(acc_, volume.grid->transform()), box_(volume.indexBox()) {
        const auto& xf = volume.grid->transform();
        if (!light.isPoint) dirIndex_ = (xf.worldToIndex(light.toLight) - xf.worldToIndex(Vec3d(0))).unitSafe();
        lightIndex_ = xf.worldToIndex(light.position);
        stopDepth_ = s.sigmaMin > 0 ? std::log(1e4) / s.sigmaMin : std::numeric_limits<double>::infinity();
    }

    float densityPath(const Vec3d& x) {
        Vec3d dir = dirIndex_;
        double tMax = std::numeric_limits<double>::infinity();
        if (light_.isPoint) {
            dir = lightIndex_ - x;
            tMax = dir.length();
            dir = dir.unitSafe();
        }
        tMax = std::min(tMax, exitDistance(x, dir));
        double D = 0;
        for (double t = 0.5 * s_.step; t < tMax; t += s_.step) {
            const double rho = sampler_.isSample(x + dir * t);
            if (std::isfinite(rho) && rho >= s_.cutoff) D += rho * s_.step / (1.0 + s_.gain * t);
            if (D > stopDepth_) break;
        }
        return float(D);
    }

private:
    // Distance from x along dir to leaving the volume's index box.
    double exitDistance(const Vec3d& x, const Vec3d& dir) const {
        double t = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a) {
            if (dir[a] > 1e-12) t = std::min(t, (box_.max()[a] + 0.5 - x[a]) / dir[a]);
            else if (dir[a] < -1e-12) t = std::min(t, (box_.min()[a] - 0.5 - x[a]) / dir[a]);
        }
        return std::max(0.0, t);
    }

    const Volume& volume_;
    const DirectionalOrPointLight& light_;
    LightCacheSettings s_;
    openvdb::FloatGrid::ConstAccessor acc_;
    Sampler sampler_;
    openvdb::CoordBBox box_;
    Vec3d dirIndex_, lightIndex_;
    double stopDepth_;
};

}  // namespace

openvdb::FloatGrid::Ptr buildLightCache(const Volume& volume, const DirectionalOrPointLight& light,
                                        const LightCacheSettings& settings) {
    openvdb::FloatGrid::Ptr cache = cacheTopology(*volume.grid, std::max(1, settings.coarsening));
    const openvdb::math::Transform& cacheXf = cache->transform();
    const openvdb::math::Transform& densityXf = volume.grid->transform();
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(cache->tree());
    leaves.foreach([&](openvdb::FloatTree::LeafNodeType& leaf, std::size_t) {
        PathMarcher marcher(volume, light, settings);
        for (auto it = leaf.beginValueOn(); it; ++it)
            it.setValue(marcher.densityPath(densityXf.worldToIndex(cacheXf.indexToWorld(it.getCoord()))));
    });
    return cache;
}

}  // namespace weft
