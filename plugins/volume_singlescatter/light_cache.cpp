#include "plugins/volume_singlescatter/light_cache.hpp"

#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "core/volume/grid/leaf_reach.hpp"
#include "core/volume/grid/octant_shift.hpp"
#include "core/volume/volume_ray.hpp"

namespace weft {

namespace {

// Where the cache's voxel 0 lies in the density's index space: a multiple
// of the cache's leaf width below the active voxels, so cache coordinates are
// positive (one top node per tree: core/volume/grid/octant_shift.hpp) and density
// leaves map onto cache voxels alike.
openvdb::Coord cacheOrigin(const openvdb::CoordBBox& active, int factor) { return widthBelow(active, 8 * factor); }

// The cache voxels (`factor` >= 2 density voxels wide) holding the active
// voxels of one density leaf, each marked once. The leaf's mask is read a
// row along z (one byte of a 64-bit word) at a time.
void markLeafCoarse(const openvdb::FloatTree::LeafNodeType& leaf, const openvdb::Coord& origin, int factor,
                    openvdb::tree::ValueAccessor<openvdb::MaskTree>& coarse) {
    constexpr int kMaxSpan = 8 / 2 + 2;  // cache voxels a leaf spans per axis
    const openvdb::Coord o = leaf.origin() - origin;
    const openvdb::Coord lo(floorDiv(o.x(), factor), floorDiv(o.y(), factor), floorDiv(o.z(), factor));
    int cell[3][8];  // the cache voxel of each local coordinate, per axis, from lo
    for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 8; ++i) cell[a][i] = floorDiv(o[a] + i, factor) - lo[a];
    std::uint8_t zBits[kMaxSpan] = {};  // the local z's of each cache voxel along z
    for (int z = 0; z < 8; ++z) zBits[cell[2][z]] |= std::uint8_t(1u << z);
    const int zCells = cell[2][7] + 1;
    bool seen[kMaxSpan][kMaxSpan][kMaxSpan] = {};
    for (int x = 0; x < 8; ++x) {
        const std::uint64_t word = leaf.getValueMask().getWord<std::uint64_t>(openvdb::Index(x));
        for (int y = 0; word && y < 8; ++y) {
            const std::uint8_t row = std::uint8_t(word >> (8 * y));
            for (int k = 0; row && k < zCells; ++k)
                if (row & zBits[k]) seen[cell[0][x]][cell[1][y]][k] = true;
        }
    }
    for (int x = 0; x < kMaxSpan; ++x)
        for (int y = 0; y < kMaxSpan; ++y)
            for (int z = 0; z < kMaxSpan; ++z)
                if (seen[x][y][z]) coarse.setValueOn(lo.offsetBy(x, y, z));
}

// The density's active voxels and tiles at the cache's scale.
openvdb::MaskTree coarseVoxels(const openvdb::FloatTree& density, const openvdb::Coord& origin, int factor) {
    openvdb::MaskTree coarse(false);
    if (factor == 1) {
        addShiftedTopology(density, -origin, coarse);
        return coarse;
    }
    // Each thread marks its leaves in a tree of its own; the trees' union is
    // the same whatever the split.
    std::vector<const openvdb::FloatTree::LeafNodeType*> leaves;
    leaves.reserve(density.leafCount());
    for (auto leaf = density.cbeginLeaf(); leaf; ++leaf) leaves.push_back(leaf.getLeaf());
    tbb::enumerable_thread_specific<openvdb::MaskTree> marked(openvdb::MaskTree(false));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 64), [&](const tbb::blocked_range<std::size_t>& r) {
        openvdb::tree::ValueAccessor<openvdb::MaskTree> acc(marked.local());
        for (std::size_t i = r.begin(); i != r.end(); ++i) markLeafCoarse(*leaves[i], origin, factor, acc);
    });
    for (const openvdb::MaskTree& part : marked) coarse.topologyUnion(part);
    auto tile = density.cbeginValueOn();
    tile.setMaxDepth(tile.getLeafDepth() - 1);  // tiles only: the leaves' voxels are marked above
    for (; tile; ++tile) {
        const openvdb::CoordBBox box = tile.getBoundingBox();
        const openvdb::Coord lo = box.min() - origin, hi = box.max() - origin;
        coarse.fill(openvdb::CoordBBox(openvdb::Coord(floorDiv(lo.x(), factor), floorDiv(lo.y(), factor), floorDiv(lo.z(), factor)),
                                       openvdb::Coord(floorDiv(hi.x(), factor), floorDiv(hi.y(), factor), floorDiv(hi.z(), factor))),
                    true, true);
    }
    return coarse;
}

// Every cache voxel a trilinear lookup of a non-empty point can reach;
// the cache's voxels are `factor` density voxels wide, centred on a density
// voxel (cache voxel c on density voxel origin + factor c): the density's
// voxels at the cache's scale, grown by one voxel.
openvdb::FloatGrid::Ptr cacheTopology(const Volume& receiver, int factor) {
    const openvdb::Coord origin = cacheOrigin(receiver.activeBox, factor);
    openvdb::FloatGrid::Ptr cache = openvdb::FloatGrid::create(0.0f);
    openvdb::math::Transform::Ptr xf = receiver.grid->transform().copy();
    xf->preTranslate(origin.asVec3d());
    xf->preScale(double(factor));
    cache->setTransform(xf);
    openvdb::MaskTree coarse = coarseVoxels(receiver.grid->tree(), origin, factor);
    coarse.voxelizeActiveTiles();
    using Leaf = openvdb::FloatTree::LeafNodeType;
    addLeavesNear(cache->tree(), coarse, 1, [](const openvdb::Coord& origin, const std::uint8_t*, const std::uint64_t* within) {
        auto leaf = std::make_unique<Leaf>(origin, 0.0f, false);
        setValueMaskWords(*leaf, within);
        return leaf;
    });
    return cache;
}

// Sets every active voxel of `cache` to value(world position of the voxel), in parallel.
template <class Make, class Value>
void fillCache(openvdb::FloatGrid& cache, const Make& makeState, const Value& value) {
    const openvdb::math::Transform& cacheXf = cache.transform();
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(cache.tree());
    leaves.foreach([&](openvdb::FloatTree::LeafNodeType& leaf, std::size_t) {
        auto state = makeState();
        for (auto it = leaf.beginValueOn(); it; ++it) it.setValue(value(*state, cacheXf.indexToWorld(it.getCoord())));
    });
}

}  // namespace

PathMarcher::PathMarcher(const Volume& occluder, const VisibleBlocks* reaching, const DirectionalOrPointLight& light,
                         const LightCacheSettings& s)
    : occluder_(occluder), reaching_(reaching), light_(light), s_(s), acc_(occluder.grid->getConstAccessor()),
      sampler_(acc_, occluder.grid->transform()), box_(occluder.indexBox()), voxelLength_(occluder.voxelLength()),
      uniform_(occluder.grid->transform().hasUniformScale()) {
    const auto& xf = occluder.grid->transform();
    if (!light.isPoint) dirIndex_ = (xf.worldToIndex(light.toLight) - xf.worldToIndex(Vec3d(0))).unitSafe();
    lightIndex_ = xf.worldToIndex(light.position);
    stopDepth_ = s.sigmaMin > 0 ? std::log(1e4) / s.sigmaMin : std::numeric_limits<double>::infinity();
}

// Voxel lengths per index unit along an index-space direction: 1 on uniform grids.
double PathMarcher::voxelLengthsPerIndexUnit(const Vec3d& dir) const {
    if (uniform_) return 1.0;
    return occluder_.grid->transform().baseMap()->applyJacobian(dir).length() / voxelLength_;
}

float PathMarcher::densityPath(const Vec3d& x) {
    Vec3d dir = dirIndex_;
    double tMax = std::numeric_limits<double>::infinity();
    if (light_.isPoint) {
        dir = lightIndex_ - x;
        tMax = dir.length();
        dir = dir.unitSafe();
    }
    tMax = std::min(tMax, exitDistance(x, dir));
    const double k = voxelLengthsPerIndexUnit(dir), step = s_.step / k;  // index units per step
    // Points outside the box (another volume's voxels, surfaces) start at
    // the entry; samples before it read nothing, so skipping them changes nothing.
    const double tEnter = entryDistance(x, dir);
    if (!(tEnter < tMax)) return 0.0f;
    // Samples at t = (n + 1/2) step, only where the path crosses the boxes
    // of cells that reach the cutoff (without them: all of [tEnter, tMax)).
    // The intervals are ordered and disjoint; nNext keeps it so at their ends.
    intervals_.clear();
    if (reaching_) reaching_->intervals(IndexRay{x, dir, tEnter, tMax}, 1.0, intervals_);
    else intervals_.push_back({tEnter, tMax});
    double D = 0, nNext = 0;
    for (const RayInterval& in : intervals_) {
        for (double n = std::max(nNext, std::ceil(in.lo / step - 0.5)); (n + 0.5) * step <= in.hi && (n + 0.5) * step < tMax; ++n) {
            nNext = n + 1;
            const double t = (n + 0.5) * step, rho = sampler_.isSample(x + dir * t);
            if (std::isfinite(rho) && rho > 0 && rho >= s_.cutoff) D += rho * s_.step / (1.0 + s_.gain * (t * k));
            if (D > stopDepth_) return float(D);
        }
    }
    return float(D);
}

// Distance from x along dir to leaving the volume's index box.
double PathMarcher::exitDistance(const Vec3d& x, const Vec3d& dir) const {
    double t = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (dir[a] > 1e-12) t = std::min(t, (box_.max()[a] + 0.5 - x[a]) / dir[a]);
        else if (dir[a] < -1e-12) t = std::min(t, (box_.min()[a] - 0.5 - x[a]) / dir[a]);
    }
    return std::max(0.0, t);
}

// Distance from x along dir to entering the box (0 inside; beyond any exit when it misses).
double PathMarcher::entryDistance(const Vec3d& x, const Vec3d& dir) const {
    double t = 0;
    for (int a = 0; a < 3; ++a) {
        const double lo = box_.min()[a] - 0.5, hi = box_.max()[a] + 0.5;
        if (dir[a] > 1e-12) t = std::max(t, (lo - x[a]) / dir[a]);
        else if (dir[a] < -1e-12) t = std::max(t, (hi - x[a]) / dir[a]);
        else if (x[a] < lo || x[a] > hi) return std::numeric_limits<double>::infinity();
    }
    return t;
}

openvdb::FloatGrid::Ptr buildLightCache(const Volume& receiver, const Volume& occluder, const VisibleBlocks* occluderReaching,
                                        const DirectionalOrPointLight& light, const LightCacheSettings& settings) {
    openvdb::FloatGrid::Ptr cache = cacheTopology(receiver, std::max(1, settings.coarsening));
    const openvdb::math::Transform& occluderXf = occluder.grid->transform();
    fillCache(*cache, [&] { return std::make_unique<PathMarcher>(occluder, occluderReaching, light, settings); },
              [&](PathMarcher& marcher, const Vec3d& p) { return marcher.densityPath(occluderXf.worldToIndex(p)); });
    return cache;
}

openvdb::FloatGrid::Ptr buildVisibilityCache(const Volume& receiver, const MeshAccel& accel,
                                             const DirectionalOrPointLight& light, int coarsening) {
    openvdb::FloatGrid::Ptr cache = cacheTopology(receiver, std::max(1, coarsening));
    fillCache(*cache, [] { return std::make_unique<int>(0); }, [&](int&, const Vec3d& p) {
        Vec3d to = light.toLight;
        double distance = std::numeric_limits<double>::infinity();
        if (light.isPoint) to = light.position - p, distance = to.length(), to = to.unitSafe();
        const Vec3f o(float(p.x()), float(p.y()), float(p.z())), d(float(to.x()), float(to.y()), float(to.z()));
        return accel.occluded(o, d, 0.0f, float(distance * (1 - 1e-4))) ? 0.0f : 1.0f;
    });
    return cache;
}

}  // namespace weft
