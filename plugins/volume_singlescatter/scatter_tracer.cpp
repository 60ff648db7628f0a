#include "plugins/volume_singlescatter/scatter_tracer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/run/counters.hpp"
#include "core/lighting/brdf.hpp"
#include "core/lighting/emitters.hpp"
#include "core/lighting/surface_shading.hpp"
#include "core/volume/grid/leaf_sampler.hpp"
#include "core/volume/media/medium.hpp"
#include "core/volume/media/transmittance.hpp"
#include "core/volume/volume_motion.hpp"
#include "core/volume/volume_ray.hpp"
#include "plugins/volume_singlescatter/shared_caches.hpp"

namespace weft {

namespace {

const Counter kLightCacheVoxels{"light_cache.voxels", "active voxels of the light caches built"};
const Counter kLightCachesBuilt{"light_cache.built", "light caches built by this render"};
const Counter kLightCachesReused{"light_cache.reused", "light caches reused from an earlier render of this process (same volumes, light, shadowstep, gain, cutoff, cache_voxel)"};

using Sampler = LeafSampler;

// NaN or Inf voxels (a broken simulation) read as empty, never as NaN light.
double finiteDensity(double rho) { return std::isfinite(rho) ? rho : 0.0; }

Vec3d expNeg(const Vec3d& v) { return Vec3d(std::exp(-v[0]), std::exp(-v[1]), std::exp(-v[2])); }

struct GridLookup {  // built in place: the sampler points at the accessor
    openvdb::FloatGrid::ConstAccessor acc;
    Sampler sampler;
    explicit GridLookup(const openvdb::FloatGrid& g) : acc(g.getConstAccessor()), sampler(acc, g.transform()) {}
};

// A Vec3s grid's lookups, when the volume has the grid.
struct Vec3Lookup {
    std::optional<openvdb::Vec3SGrid::ConstAccessor> accessor;
    std::optional<Vec3LeafSampler> sampler;  // through accessor
    explicit Vec3Lookup(const openvdb::Vec3SGrid::ConstPtr& grid) {
        if (!grid) return;
        accessor.emplace(grid->getConstAccessor());
        sampler.emplace(*accessor, grid->transform());
    }
    explicit operator bool() const { return sampler.has_value(); }
    Vec3d at(const Vec3d& ijk) { return toVec3d(sampler->isSample(ijk)); }
};

struct VolumeLookup : GridLookup {
    std::optional<VdbIntersector> primary, shadow;  // where the volume has an intersector
    Vec3Lookup emission, color;
    std::optional<MotionLookup> motion;
    const openvdb::math::Transform* xf;
    explicit VolumeLookup(const ScatterVolume& v)
        : GridLookup(*v.volume->grid), emission(v.volume->emission), color(v.volume->color), xf(&v.volume->grid->transform()) {
        if (v.intersector) primary.emplace(*v.intersector), shadow.emplace(*v.intersector);
        emplaceMotion(motion, *v.volume);
    }
    // Where the volume's grids are read for world point p at shutter time
    // `time` (frames): p's index point, advected back when the volume moves.
    Vec3d indexAt(const Vec3d& p, double time) {
        const Vec3d ijk = xf->worldToIndex(p);
        return motion && time != 0 ? Vec3d(motion->advected(ijk, time)) : ijk;
    }
    bool movesAt(double time) const { return motion && time != 0; }
    // The scattering tint at an index point (1: untinted).
    Vec3d tint(const Vec3d& ijk) { return color ? color.at(ijk) : Vec3d(1.0); }
};

// Emission e (per march unit) over a step of length h whose transmittance
// is dT at extinction sigma (per march unit): e (1 - dT) / sigma per
// channel, e h where sigma h -> 0.
Vec3d emittedOver(const Vec3d& e, const Vec3d& sigma, const Vec3d& dT, double h) {
    Vec3d out;
    for (int c = 0; c < 3; ++c) out[c] = e[c] * (sigma[c] * h > 1e-6 ? (1.0 - dT[c]) / sigma[c] : h * (1.0 - 0.5 * sigma[c] * h));
    return out;
}

struct Crossing {  // one volume on the current camera ray
    std::size_t volume;
    VdbRay ray;         // index space
    double perU;        // index units per march unit
    double depthScale;  // voxel lengths per march unit
};


// Light towards p: unit direction, distance, and radiance scale.
struct LightAt {
    Vec3d toLight, color;
    double distance;
    bool valid;
};

LightAt lightAt(const DirectionalOrPointLight& light, const Vec3d& p) {
    if (!light.isPoint) return {light.toLight, light.color, std::numeric_limits<double>::infinity(), true};
    Vec3d to = light.position - p;
    const double d = to.length();
    if (d < 1e-12) return {to, light.color, d, false};
    return {to / d, light.color / (d * d), d, true};
}

// What OpenVDB's intersector can report: whole leaf nodes (8^3 voxels), a
// voxel beyond for safety, so the BVH prunes exactly the rays it would miss.
BBoxd intersectorWorldBox(const Volume& v) {
    openvdb::CoordBBox leaves;
    v.grid->tree().evalLeafBoundingBox(leaves);
    leaves.expand(1 + (v.motion ? int(std::ceil(v.motionReach)) : 0));  // and where a moving volume reaches
    return worldBoxOf(v.grid->transform(), leaves.min().asVec3d(), leaves.max().asVec3d() + Vec3d(1.0));
}

}  // namespace

class ScatterTracer::Row {
public:
    std::deque<VolumeLookup> volumes;
    std::deque<GridLookup> density, visibility;
    std::deque<PathMarcher> marchers;  // [light][occluder], for surfaces
    std::vector<Crossing> crossings;
    std::vector<RayInterval> spans;  // march units
    std::vector<VdbRay::TimeSpan> hits;
    std::vector<Share> shares;
    std::vector<std::uint32_t> crossed;  // volumes whose boxes the current ray meets
    double time = 0;                     // the camera sample's shutter time, frames from the frame
    Counts counts;
};

ScatterTracer::ScatterTracer(const Scene& scene, const ScatterParams& params, std::vector<ScatterVolume> volumes,
                             const MeshAccel* accel, float eps)
    : scene_(scene), params_(params), volumes_(std::move(volumes)), accel_(accel), eps_(eps), moving_(scene.volumesMove()) {
    if (volumes_.size() < 2) return;
    std::vector<BBoxd> boxes;
    for (const ScatterVolume& v : volumes_) boxes.push_back(intersectorWorldBox(*v.volume));
    bvh_ = VolumeBvh(std::move(boxes));
}

// The volumes whose world boxes origin + t dir meets on [0, tMax], ascending.
const std::vector<std::uint32_t>& ScatterTracer::crossed(const Vec3d& origin, const Vec3d& dir, double tMax, Row& row) const {
    if (bvh_.size() > 0) {
        bvh_.query(origin, dir, tMax, row.crossed);
    } else {
        row.crossed.resize(volumes_.size());
        for (std::uint32_t i = 0; i < row.crossed.size(); ++i) row.crossed[i] = i;
    }
    return row.crossed;
}

static LightCacheSettings cacheSettings(const ScatterParams& p, const ScatterVolume& occluder) {
    const double sigmaMin = std::min({occluder.sigmaT[0], occluder.sigmaT[1], occluder.sigmaT[2]});
    return {p.shadowStep, p.gain, p.cutoff, sigmaMin, p.cacheCoarsening};
}

void ScatterTracer::buildCaches(RenderContext& ctx) {
    ScopedTimer timer(ctx.timings, "light_cache");
    std::int64_t voxels = 0, built = 0, reused = 0;
    if (!params_.lights.empty())  // the leaps serve the lights' marches only: none without a point or directional light
        for (const ScatterVolume& v : volumes_)
            cacheReaching_.push_back(sharedReaching(*v.volume, float(params_.cutoff), VisibleBlocks::Within::Anywhere));
    for (const DirectionalOrPointLight& light : params_.lights)
        for (const ScatterVolume& receiver : volumes_) {
            for (std::size_t o = 0; o < volumes_.size(); ++o) {
                const ScatterVolume& occluder = volumes_[o];
                SharedLightCache cache =
                    sharedLightCache(*receiver.volume, *occluder.volume, cacheReaching_[o].get(), light, cacheSettings(params_, occluder));
                if (cache.reused) ++reused;
                else ++built, voxels += std::int64_t(cache.grid->activeVoxelCount());
                densityCaches_.push_back(std::move(cache.grid));
            }
            if (accel_) visibilityCaches_.push_back(buildVisibilityCache(*receiver.volume, *accel_, light, params_.cacheCoarsening));
        }
    ctx.counters.add(kLightCacheVoxels, voxels);
    ctx.counters.add(kLightCachesBuilt, built);
    ctx.counters.add(kLightCachesReused, reused);
}

void ScatterTracer::RowDeleter::operator()(Row* row) const { delete row; }

std::unique_ptr<ScatterTracer::Row, ScatterTracer::RowDeleter> ScatterTracer::row() const {
    std::unique_ptr<Row, RowDeleter> row(new Row);
    for (const ScatterVolume& v : volumes_) row->volumes.emplace_back(v);
    for (const auto& c : densityCaches_) row->density.emplace_back(*c);
    for (const auto& c : visibilityCaches_) row->visibility.emplace_back(*c);
    if (accel_ && params_.estimator == ShadowEstimator::Cached)
        for (const DirectionalOrPointLight& light : params_.lights)
            for (std::size_t o = 0; o < volumes_.size(); ++o)
                row->marchers.emplace_back(*volumes_[o].volume, cacheReaching_[o].get(), light, cacheSettings(params_, volumes_[o]));
    return row;
}

const ScatterTracer::Counts& ScatterTracer::counts(const Row& row) { return row.counts; }

Vec3d ScatterTracer::radiance(const Ray& ray, float offset, double time, Row& row, Rng& rng, Vec3d& T, bool& surface, bool seen) const {
    Vec3d L(0.0);
    row.time = time;
    SurfaceHit hit;
    if (accel_) hit = firstSurface(*accel_, ray);
    surface = hit.valid();
    const double tSurface = surface ? double(hit.t) : std::numeric_limits<double>::infinity();
    const bool open = !seen || marchVolumes(ray, tSurface, offset, row, rng, T, L);  // unseen: no sample, nothing to add
    if (!open || !surface) return L;
    return L + T * surfaceRadiance(ray, hit, row, rng);
}

std::optional<ScreenFootprint> ScatterTracer::footprint(const CameraRays& rays, int width, int height) const {
    ScreenFootprint out(rays, width, height);
    for (const ScatterVolume& v : volumes_) {
        if (!v.reaching) return std::nullopt;
        out.addBlocks(*v.reaching, v.volume->grid->transform());
    }
    return out;
}

// The volumes this ray crosses, in march units u (voxel lengths of the
// finest one), with their occupied spans merged; samples sit at
// u = step * (k + offset) for integer k (offset 0: vdb_render's
// step * ceil(t0 / step) phase). False once the ray is opaque.
bool ScatterTracer::marchVolumes(const Ray& ray, double tSurface, float offset, Row& row, Rng& rng, Vec3d& T, Vec3d& L) const {
    const VdbRay wray(ray.origin, ray.dir);
    row.crossings.clear();
    double unitLength = std::numeric_limits<double>::max();
    for (std::uint32_t i : crossed(ray.origin, ray.dir, std::numeric_limits<double>::infinity(), row)) {
        const VdbRay iray = volumes_[i].indexRay(wray);
        const VdbRay oray = volumes_[i].occupancyRay(iray);
        VolumeLookup& look = row.volumes[i];
        if (!(look.primary ? look.primary->setIndexRay(oray) : volumes_[i].crosses(oray))) continue;
        row.crossings.push_back({i, iray, 0, 0});
        unitLength = std::min(unitLength, volumes_[i].voxelLength);
    }
    if (row.crossings.empty()) return true;
    const double speed = ray.dir.length();
    row.spans.clear();
    for (Crossing& c : row.crossings) {
        const ScatterVolume& v = volumes_[c.volume];
        const bool unit = v.uniform && v.voxelLength == unitLength;  // index units are march units exactly
        c.perU = unit ? 1.0 : unitLength * v.indexSpeed(ray.dir) / speed;
        c.depthScale = unit ? 1.0 : unitLength / v.voxelLength;
        if (v.reaching) {
            v.reaching->intervals(IndexRay{c.ray.eye(), c.ray.dir(), c.ray.t0(), c.ray.t1()}, c.perU, row.spans);
            continue;
        }
        row.volumes[c.volume].primary.value().hits(row.hits);
        for (const auto& h : row.hits) row.spans.push_back({h.t0 / c.perU, h.t1 / c.perU});
    }
    if (row.crossings.size() > 1) mergeIntervals(row.spans);
    const Crossing& first = row.crossings.front();
    const double uSurface = std::isfinite(tSurface) ? tSurface * volumes_[first.volume].indexSpeed(ray.dir) / first.perU : tSurface;
    if (row.crossings.size() == 1) return marchOne(ray, uSurface, offset, row, rng, T, L);
    const double h = params_.step;
    for (const RayInterval& span : row.spans) {
        for (double t = h * (std::ceil(span.lo / h - offset) + offset); t <= span.hi; t += h) {
            if (t >= uSurface) return true;
            const Vec3d pw = volumes_[first.volume].worldPos(first.ray, t * first.perU);
            row.shares.clear();
            Vec3d sigma(0.0), glow(0.0);
            for (const Crossing& c : row.crossings) {
                VolumeLookup& look = row.volumes[c.volume];
                const Vec3d ijk = look.indexAt(pw, row.time);
                const double rho = finiteDensity(look.sampler.isSample(ijk));
                ++row.counts.samples;
                if (look.emission) glow += look.emission.at(ijk) * c.depthScale;
                if (!(rho > 0) || rho < params_.cutoff) continue;  // no share: it would pick a receiver with no cache here
                row.shares.push_back({c.volume, rho * c.depthScale, look.tint(ijk)});
                sigma += volumes_[c.volume].sigmaT * row.shares.back().weight;
            }
            if (row.shares.empty() && glow == Vec3d(0.0)) continue;
            const Vec3d dT = row.shares.size() == 1 ? expNeg(volumes_[row.shares[0].volume].sigmaT * (row.shares[0].weight * h))
                                                    : expNeg(sigma * h);
            if (!row.shares.empty()) L += inscatter(pw, ray.dir, row.shares, sigma, row, rng) * T * (Vec3d(1.0) - dT);
            if (glow != Vec3d(0.0)) L += T * emittedOver(glow, sigma, dT, h);
            T *= dT;
            if (T.lengthSqr() < params_.cutoff) return false;
        }
    }
    return true;
}

// One volume on the ray, the common case: its lookups hoisted out of the loop.
bool ScatterTracer::marchOne(const Ray& ray, double uSurface, float offset, Row& row, Rng& rng, Vec3d& T, Vec3d& L) const {
    const Crossing& c = row.crossings.front();
    const ScatterVolume& v = volumes_[c.volume];
    VolumeLookup& look = row.volumes[c.volume];
    Sampler& sampler = look.sampler;
    Vec3Lookup* emission = look.emission ? &look.emission : nullptr;
    const double time = row.time;
    row.shares.assign(1, Share{c.volume, 0.0, Vec3d(1.0)});
    const double h = params_.step, cutoff = params_.cutoff;
    std::int64_t n = 0;
    bool more = true;
    for (const RayInterval& span : row.spans) {
        for (double t = h * (std::ceil(span.lo / h - offset) + offset); t <= span.hi && more; t += h) {
            if (t >= uSurface) break;
            const Vec3d pw = v.worldPos(c.ray, t * c.perU), ijk = look.indexAt(pw, time);
            const double rho = finiteDensity(sampler.isSample(ijk));
            ++n;
            const Vec3d glow = emission ? emission->at(ijk) * c.depthScale : Vec3d(0.0);
            const bool scatters = rho > 0 && rho >= cutoff;
            if (!scatters && glow == Vec3d(0.0)) continue;
            row.shares[0].weight = scatters ? rho * c.depthScale : 0.0;
            if (look.color) row.shares[0].tint = look.tint(ijk);
            const Vec3d sigma = v.sigmaT * row.shares[0].weight, dT = expNeg(sigma * h);
            if (scatters) L += inscatter(pw, ray.dir, row.shares, v.sigmaT, row, rng) * T * (Vec3d(1.0) - dT);
            if (emission) L += T * emittedOver(glow, sigma, dT, h);
            T *= dT;
            more = T.lengthSqr() >= cutoff;
        }
        if (!more) break;
    }
    row.counts.samples += n;
    return more;
}

double ScatterTracer::phase(const ScatterVolume& v, double cosTheta) const {
    // phaseScale is 1 / 4pi when physical: the medium's HG as it stands; else
    // vdb_render's convention, isotropic = 1.
    if (v.phase == Phase::Isotropic) return params_.phaseScale;
    return params_.phaseScale * (4.0 * M_PI) * henyeyGreenstein(v.g, cosTheta);
}

// Light arriving at world point p, times albedo and phase, summed over
// lights; several volumes scatter in proportion to sigma_s of each.
Vec3d ScatterTracer::inscatter(const Vec3d& p, const Vec3d& viewDir, const std::vector<Share>& shares, const Vec3d& sigmaT,
                               Row& row, Rng& rng) const {
    Vec3d sum(0.0);
    for (std::size_t i = 0; i < params_.lights.size(); ++i) {
        const LightAt l = lightAt(params_.lights[i], p);
        if (!l.valid) continue;
        const Vec3d shadowT = shadow(i, p, l.toLight, l.distance, shares.front().volume, row, rng);
        sum += l.color * shadowT * scattering(shares, sigmaT, l.toLight.dot(viewDir));
    }
    if (params_.emitters) {
        const EmitterLight e = emitterLight(p, row, rng);
        if (e.valid) sum += e.radiance * scattering(shares, sigmaT, e.toLight.dot(viewDir));
    }
    return sum;
}

// Albedo times phase of the sample's volumes, as one medium.
Vec3d ScatterTracer::scattering(const std::vector<Share>& shares, const Vec3d& sigmaT, double cosTheta) const {
    if (shares.size() == 1) {
        const ScatterVolume& v = volumes_[shares.front().volume];
        return v.albedo * shares.front().tint * phase(v, cosTheta);
    }
    Vec3d mix(0.0);
    for (const Share& s : shares)
        mix += volumes_[s.volume].sigmaT * volumes_[s.volume].albedo * s.tint * (s.weight * phase(volumes_[s.volume], cosTheta));
    for (int c = 0; c < 3; ++c) mix[c] = sigmaT[c] > 0 ? mix[c] / sigmaT[c] : 0.0;
    return mix;
}

// One point on the emissive triangles, picked by power, seen from p
// through the meshes and volumes (traced: the cache holds delta lights only).
ScatterTracer::EmitterLight ScatterTracer::emitterLight(const Vec3d& p, Row& row, Rng& rng) const {
    const float u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    const EmitterSample e = scene_.emitters().sample(u0, u1, u2);
    const EmitterView v = viewFrom(e, toVec3f(p));
    if (!(v.distance > 2 * eps_) || !(e.pdfArea > 0) || !(v.cosLight > 0)) return {};
    const Vec3d to = toVec3d(v.wi), T = tracedShadow(p, to, v.distance, row, rng);
    return {to, toVec3d(e.radiance) * T * (double(v.cosLight) / (double(v.distance2) * double(e.pdfArea))), true};
}

// Transmittance from p (inside `receiver`) to the light: the cache, or shadow rays.
Vec3d ScatterTracer::shadow(std::size_t light, const Vec3d& p, const Vec3d& toLight, double distance, std::size_t receiver,
                            Row& row, Rng& rng) const {
    if (params_.estimator != ShadowEstimator::Cached) return tracedShadow(p, toLight, distance, row, rng);
    // A moving receiver's cache is read where its sample came from: exact
    // for a volume translating as a whole under directional lights.
    VolumeLookup& look = row.volumes[receiver];
    const bool moving = look.movesAt(row.time);
    const Vec3d q = moving ? look.xf->indexToWorld(look.indexAt(p, row.time)) : p;
    Vec3d T(1.0);
    for (std::size_t o = 0; o < volumes_.size(); ++o) {
        ++row.counts.shadowSamples;
        T *= expNeg(volumes_[o].sigmaT * row.density[cacheIndex(light, receiver, o)].sampler.wsSample(q));
    }
    if (!accel_) return T;
    if (!moving) return T * std::clamp(double(row.visibility[light * volumes_.size() + receiver].sampler.wsSample(p)), 0.0, 1.0);
    ++row.counts.meshShadowRays;  // the meshes stay where the visibility cache saw them; the sample does not
    return accel_->occluded(toVec3f(p), toVec3f(toLight), 0.0f, float(distance * (1 - 1e-4))) ? Vec3d(0.0) : T;
}

// Shadow rays: the meshes (Embree), then every volume (ratio tracking or the fixed-step march).
Vec3d ScatterTracer::tracedShadow(const Vec3d& p, const Vec3d& toLight, double distance, Row& row, Rng& rng) const {
    if (accel_) {
        ++row.counts.meshShadowRays;
        if (accel_->occluded(toVec3f(p), toVec3f(toLight), 0.0f, float(distance * (1 - 1e-4)))) return Vec3d(0.0);
    }
    Vec3d T(1.0);
    for (std::uint32_t o : crossed(p, toLight, distance, row)) T = shadowThrough(o, p, toLight, distance, row, rng, T);
    return T;
}

// T times the transmittance of one volume along the shadow ray.
Vec3d ScatterTracer::shadowThrough(std::size_t volume, const Vec3d& p, const Vec3d& toLight, double distance, Row& row,
                                   Rng& rng, Vec3d T) const {
    const ScatterVolume& v = volumes_[volume];
    VolumeLookup& look = row.volumes[volume];
    // vdb_render's shadow rays start at t = Delta, so the first fixed step
    // lands one step away from p; the intersector works in index times.
    const VdbRay iray = v.indexRay(VdbRay(p, toLight, openvdb::math::Delta<double>::value(), distance));
    VdbIntersector& intersector = look.shadow.value();  // built for every volume a shadow ray can cross
    if (!intersector.setIndexRay(v.occupancyRay(iray))) return T;
    intersector.hits(row.hits);
    const double k = v.voxelLengthsPerIndexUnit(iray.dir());  // 1 on uniform grids
    auto sigma = [&](double t) {
        const double rho = finiteDensity(look.sampler.isSample(look.indexAt(v.worldPos(iray, t), row.time)));
        ++row.counts.shadowSamples;
        return !(rho > 0) || rho < params_.cutoff ? Vec3d(0.0) : v.sigmaT * (rho * k / (1.0 + (t * k) * params_.gain));
    };
    for (const auto& span : row.hits) {
        if (params_.estimator == ShadowEstimator::Raymarch) {
            T = marchTransmittance(sigma, span.t0, span.t1, params_.shadowStep / k, params_.cutoff, T);
            if (T.lengthSqr() < params_.cutoff) break;
        } else {
            const double majorant = std::max({v.sigmaT[0], v.sigmaT[1], v.sigmaT[2]}) * v.majorantDensity * k;
            T *= ratioTracking(sigma, span.t0, span.t1, majorant, rng);
        }
    }
    return T;
}

// Emission plus the lights on the Lambert + glossy BRDF, through meshes and volumes.
Vec3d ScatterTracer::surfaceRadiance(const Ray& ray, const SurfaceHit& hit, Row& row, Rng& rng) const {
    const Vec3d p = ray.origin + ray.dir * double(hit.t);
    const Vec3f wo = -toVec3f(ray.dir).unitSafe();
    const Material& mat = scene_.materials[accel_->material(hit.geom, hit.prim)];
    const bool front = hit.normal.dot(wo) > 0;
    const Vec3f n = front ? hit.normal : -hit.normal;
    const Brdf brdf = Brdf::of(mat);
    const Vec3d origin = p + toVec3d(n) * double(eps_);
    Vec3d L(0.0);
    if (front && mat.emissive()) L = toVec3d(mat.emission);
    for (std::size_t i = 0; i < params_.lights.size(); ++i) {
        const LightAt l = lightAt(params_.lights[i], origin);
        const Vec3f wi = toVec3f(l.toLight);
        const float cosI = n.dot(wi);
        if (!l.valid || cosI <= 0) continue;
        const Vec3f f = brdf.eval(wo, wi, n) * cosI;
        L += toVec3d(f) * l.color * surfaceShadow(i, origin, l.toLight, l.distance, row, rng);
    }
    if (params_.emitters) {
        const EmitterLight e = emitterLight(origin, row, rng);
        const Vec3f wi = toVec3f(e.toLight);
        if (e.valid && n.dot(wi) > 0) L += toVec3d(brdf.eval(wo, wi, n) * n.dot(wi)) * e.radiance;
    }
    return L;
}

// The cached estimator marches the cache's rule from the surface point
// itself (surfaces lie outside the volumes' cache voxels).
Vec3d ScatterTracer::surfaceShadow(std::size_t light, const Vec3d& p, const Vec3d& toLight, double distance, Row& row,
                                   Rng& rng) const {
    if (params_.estimator != ShadowEstimator::Cached || moving_) return tracedShadow(p, toLight, distance, row, rng);
    ++row.counts.meshShadowRays;
    if (accel_->occluded(toVec3f(p), toVec3f(toLight), 0.0f, float(distance * (1 - 1e-4)))) return Vec3d(0.0);
    Vec3d T(1.0);
    for (std::size_t o = 0; o < volumes_.size(); ++o) {
        ++row.counts.shadowSamples;
        T *= expNeg(volumes_[o].sigmaT * row.marchers[light * volumes_.size() + o].densityPathFromWorld(p));
    }
    return T;
}

}  // namespace weft
