#include "core/volume/media/medium.hpp"

#include <openvdb/tools/Interpolation.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/volume/volume_ray.hpp"

namespace weft {

namespace {

// A ray that crosses absurd extinction (1e12 per voxel) in a trilinear ramp
// would meet ~1e10 null collisions; past this many it is taken as opaque.
// Ordinary media need orders of magnitude fewer.
constexpr int kMaxCollisions = 1 << 16;

double maxChannel(const Vec3d& v) { return std::max({v[0], v[1], v[2]}); }
double minChannel(const Vec3d& v) { return std::min({v[0], v[1], v[2]}); }
double mean(const Vec3d& v) { return (v[0] + v[1] + v[2]) / 3.0; }
Vec3d abs3(const Vec3d& v) { return Vec3d(std::abs(v[0]), std::abs(v[1]), std::abs(v[2])); }

double usableDensity(double rho) { return std::isfinite(rho) && rho > 0 ? rho : 0.0; }

// Exponential free path at rate m from a uniform number.
double freePath(double majorant, Rng& rng) { return -std::log1p(-rng.uniformDouble()) / majorant; }

constexpr int kBrickLog2 = 3;  // 8^3 voxels, OpenVDB's leaf
constexpr int kBrick = 1 << kBrickLog2;

openvdb::Coord brickOf(const openvdb::Coord& voxel) {
    return openvdb::Coord(voxel.x() >> kBrickLog2, voxel.y() >> kBrickLog2, voxel.z() >> kBrickLog2);
}

void raise(openvdb::FloatGrid::Accessor& acc, const openvdb::Coord& c, float v) {
    if (v > acc.getValue(c)) acc.setValue(c, v);
}

// Largest usable density per brick, then spread to the 26 neighbours so a
// brick's bound covers trilinear lookups that reach into the next brick.
openvdb::FloatGrid::Ptr densityBricks(const openvdb::FloatGrid& grid) {
    const float background = float(usableDensity(grid.background()));
    auto raw = openvdb::FloatGrid::create(background), bricks = openvdb::FloatGrid::create(background);
    auto rawAcc = raw->getAccessor(), acc = bricks->getAccessor();
    for (auto it = grid.tree().cbeginValueAll(); it; ++it) {
        const float v = float(usableDensity(*it));
        if (v <= background) continue;
        const openvdb::CoordBBox box = it.getBoundingBox();
        if (box.volume() == 1) {
            raise(rawAcc, brickOf(box.min()), v);
            continue;
        }
        // A tile: every brick it covers (tiles are whole bricks or larger).
        const openvdb::CoordBBox bb(brickOf(box.min()), brickOf(box.max()));
        for (auto c = bb.begin(); c; ++c) raise(rawAcc, *c, v);
    }
    for (auto it = raw->cbeginValueOn(); it; ++it)
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) raise(acc, it.getCoord().offsetBy(dx, dy, dz), *it);
    return bricks;
}

// 1 in every brick whose voxels (or a neighbour brick's) emit.
openvdb::FloatGrid::Ptr emissiveBricks(const openvdb::Vec3SGrid& emission) {
    auto raw = openvdb::FloatGrid::create(0.0f), bricks = openvdb::FloatGrid::create(0.0f);
    auto rawAcc = raw->getAccessor(), acc = bricks->getAccessor();
    for (auto it = emission.tree().cbeginValueOn(); it; ++it) {
        if (*it == openvdb::Vec3s(0.0f)) continue;
        const openvdb::CoordBBox box = it.getBoundingBox();
        const openvdb::CoordBBox bb(brickOf(box.min()), brickOf(box.max()));
        for (auto c = bb.begin(); c; ++c) rawAcc.setValue(*c, 1.0f);
    }
    for (auto it = raw->cbeginValueOn(); it; ++it)
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) acc.setValue(it.getCoord().offsetBy(dx, dy, dz), 1.0f);
    return bricks;
}

}  // namespace

Medium::Medium(const std::vector<Volume>& volumes) {
    for (const Volume& v : volumes) {
        if (v.empty()) continue;
        const double perWorld = 1.0 / v.voxelLength();
        Entry e{&v, v.medium.absorb * perWorld, v.medium.scatter * perWorld, 0.0, nullptr, nullptr};
        e.coefficientMax = maxChannel(e.absorb + e.scatter);
        if (!(e.coefficientMax > 0) && !v.emission) continue;  // nothing to meet
        const int reach = v.motion ? brickReach(v.motionReach) : 0;  // a moving volume's bricks bound where it moves
        e.bricks = dilatedBrickBounds(densityBricks(*v.grid), reach);
        if (v.emission) e.emissiveBricks = dilatedBrickBounds(emissiveBricks(*v.emission), reach), e.emissionRate = perWorld;
        volumes_.push_back(e);
    }
    if (volumes_.size() < 2) return;
    std::vector<BBoxd> boxes;
    for (const Entry& e : volumes_) boxes.push_back(e.volume->worldBox());
    bvh_ = VolumeBvh(std::move(boxes));
}

MediumRay::MediumRay(const Medium& medium) : medium_(medium) {
    for (const auto& e : medium.volumes_) {
        accessors_.push_back(e.volume->grid->getConstAccessor());
        brickAccessors_.push_back(e.bricks->getConstAccessor());
        emissionAccessors_.emplace_back();
        if (e.volume->emission) emissionAccessors_.back().emplace(e.volume->emission->getConstAccessor());
        colorAccessors_.emplace_back();
        if (e.volume->color) colorAccessors_.back().emplace(e.volume->color->getConstAccessor());
        emplaceMotion(motions_.emplace_back(), *e.volume);
    }
    for (std::size_t i = 0; i < accessors_.size(); ++i) {  // after the last push_back: they point into the accessors
        const Volume& v = *medium.volumes_[i].volume;
        samplers_.emplace_back(accessors_[i], v.grid->transform());
        emissionSamplers_.emplace_back();
        if (emissionAccessors_[i]) emissionSamplers_.back().emplace(*emissionAccessors_[i], v.emission->transform());
        colorSamplers_.emplace_back();
        if (colorAccessors_[i]) colorSamplers_.back().emplace(*colorAccessors_[i], v.color->transform());
    }
}

// The segment's current brick: its density bound times the largest
// coefficient, raised to the emission floor where the brick emits.
double MediumRay::brickMajorant(const MediumSegment& s) {
    const Medium::Entry& e = medium_.volumes_[s.volume];
    const double m = brickAccessors_[s.volume].getValue(s.brick) * e.coefficientMax;
    if (!e.emissiveBricks || !(e.emissiveBricks->tree().getValue(s.brick) > 0)) return m;
    return std::max(m, e.emissionRate);
}

// Amanatides-Woo in brick coordinates, parametrised by world distance.
void MediumRay::startBricks(MediumSegment& s) {
    const double t = s.t0;
    const Vec3d p = (s.indexOrigin + s.indexStep * t) / double(kBrick), dir = s.indexStep / double(kBrick);
    for (int a = 0; a < 3; ++a) {
        s.brick[a] = int(std::floor(p[a]));
        if (dir[a] > 0) s.crossing[a] = t + (s.brick[a] + 1 - p[a]) / dir[a], s.crossingStep[a] = 1 / dir[a];
        else if (dir[a] < 0) s.crossing[a] = t + (s.brick[a] - p[a]) / dir[a], s.crossingStep[a] = -1 / dir[a];
        else s.crossing[a] = s.crossingStep[a] = std::numeric_limits<double>::infinity();
    }
    s.exit = std::min({s.crossing[0], s.crossing[1], s.crossing[2], s.t1});
    s.majorant = brickMajorant(s);
}

void MediumRay::nextBrick(MediumSegment& s) {
    const int a = s.crossing[0] <= s.crossing[1] ? (s.crossing[0] <= s.crossing[2] ? 0 : 2) : (s.crossing[1] <= s.crossing[2] ? 1 : 2);
    s.brick[a] += s.indexStep[a] > 0 ? 1 : -1;
    s.crossing[a] += s.crossingStep[a];
    s.exit = std::min({s.crossing[0], s.crossing[1], s.crossing[2], s.t1});
    s.majorant = brickMajorant(s);
}

void MediumRay::reset(const Vec3d& origin, const Vec3d& dir, double tMax) {
    segments_.clear();
    end_ = 0;
    if (medium_.bvh_.size() == 0) {
        for (std::uint32_t i = 0; i < medium_.volumes_.size(); ++i) addSegment(i, origin, dir, tMax);
        return;
    }
    medium_.bvh_.query(origin, dir, tMax, crossed_);
    for (std::uint32_t i : crossed_) addSegment(i, origin, dir, tMax);
}

void MediumRay::addSegment(std::uint32_t i, const Vec3d& origin, const Vec3d& dir, double tMax) {
    const Medium::Entry& e = medium_.volumes_[i];
    const auto& xf = e.volume->grid->transform();
    const Vec3d io = xf.worldToIndex(origin), step = xf.worldToIndex(origin + dir) - io;
    const double perWorld = step.length();  // index length per world length
    if (!(perWorld > 0)) return;
    const auto clip = toIndexRay(Ray{origin, dir}, *e.volume);
    if (!clip) return;
    MediumSegment s{i, clip->t0 / perWorld, std::min(clip->t1 / perWorld, tMax), 0.0, io, step, {}, {}, {}, 0.0};
    if (!(s.t1 > s.t0)) return;
    startBricks(s);
    segments_.push_back(s), end_ = std::max(end_, s.t1);
}

MajorantSpan MediumRay::majorantAt(double t) {
    MajorantSpan span{0.0, end_};
    for (MediumSegment& s : segments_) {
        if (t < s.t0) {
            span.next = std::min(span.next, s.t0);
        } else if (t < s.t1) {
            while (t >= s.exit) nextBrick(s);
            span.majorant += s.majorant;
            span.next = std::min(span.next, s.exit);
        }
    }
    return span;
}

MediumCoefficients MediumRay::at(double t) {
    MediumCoefficients c;
    lobes_.clear();
    for (const MediumSegment& s : segments_) {
        if (t < s.t0 || t >= s.t1) continue;
        const Medium::Entry& e = medium_.volumes_[s.volume];
        Vec3d ijk = s.indexOrigin + s.indexStep * t;
        if (motions_[s.volume] && time_ != 0) ijk = motions_[s.volume]->advected(ijk, time_);
        const double rho = usableDensity(samplers_[s.volume].isSample(ijk));
        ++lookups;
        Vec3d scatter = e.scatter * rho;
        c.extinction += e.absorb * rho + scatter;  // the colour moves scattering to absorption: the sum stays
        if (colorSamplers_[s.volume]) scatter *= toVec3d(colorSamplers_[s.volume]->isSample(ijk));
        c.scattering += scatter;
        if (emissionSamplers_[s.volume]) c.emission += toVec3d(emissionSamplers_[s.volume]->isSample(ijk)) * e.emissionRate;
        lobes_.push_back({e.volume->medium.g, scatter});
    }
    c.g = lobes_.size() == 1 ? lobes_[0].g : 0.0;
    return c;
}

double MediumRay::pickPhase(Rng& rng, Vec3d& throughput) const {
    if (lobes_.size() == 1) return lobes_[0].g;
    Vec3d total(0.0);
    double sum = 0;
    for (const Lobe& l : lobes_) total += l.scattering, sum += mean(l.scattering);
    if (!(sum > 0)) return 0.0;
    double u = rng.uniformDouble() * sum;
    for (const Lobe& l : lobes_) {
        const double p = mean(l.scattering);
        if (u >= p && &l != &lobes_.back()) {
            u -= p;
            continue;
        }
        if (!(p > 0)) break;  // only by rounding at the end of the list
        for (int c = 0; c < 3; ++c) throughput[c] *= total[c] > 0 ? l.scattering[c] / total[c] * (sum / p) : 0.0;
        return l.g;
    }
    throughput = Vec3d(0.0);
    return 0.0;
}

double henyeyGreenstein(double g, double cosTheta) {
    const double d = 1.0 + g * g - 2.0 * g * cosTheta;
    return (1.0 - g * g) / (4.0 * M_PI * d * std::sqrt(d));
}

double sampleHenyeyGreensteinCos(double g, double u) {
    if (std::abs(g) < 1e-3) return 1.0 - 2.0 * u;
    const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    return std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

Vec3d sampleHenyeyGreenstein(const Vec3d& d, double g, double u1, double u2) {
    const double cosT = sampleHenyeyGreensteinCos(g, u1), sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
    const double phi = 2.0 * M_PI * u2;
    // An orthonormal frame around d (Duff et al. 2017).
    const double sign = std::copysign(1.0, d.z()), a = -1.0 / (sign + d.z()), b = d.x() * d.y() * a;
    const Vec3d t(1.0 + sign * d.x() * d.x() * a, sign * b, -sign * d.x()), bt(b, sign + d.y() * d.y() * a, -d.y());
    return (t * (sinT * std::cos(phi)) + bt * (sinT * std::sin(phi)) + d * cosT).unitSafe();
}

// Both estimators walk the piecewise-constant majorant: a free path that
// passes the end of a span restarts at it (exponentials are memoryless).
template <class AtCollision>
static bool trackCollisions(MediumRay& ray, Rng& rng, std::int64_t& collisions, const AtCollision& atCollision) {
    double t = 0;
    for (int n = 0; n < kMaxCollisions;) {
        const MajorantSpan span = ray.majorantAt(t);
        if (t >= ray.end()) return true;
        if (!(span.majorant > 0)) {
            t = span.next;
            continue;
        }
        const double next = t + freePath(span.majorant, rng);
        if (next >= span.next) {
            t = span.next;
            continue;
        }
        t = next, ++n, ++collisions;
        if (!atCollision(t, span.majorant)) return true;
    }
    return false;  // capped: taken as opaque
}

Vec3d ratioTrackingTransmittance(MediumRay& ray, Rng& rng, std::int64_t& collisions) {
    Vec3d T(1.0);
    const bool done = trackCollisions(ray, rng, collisions, [&](double t, double m) {
        const Vec3d s = ray.at(t).extinction;
        for (int c = 0; c < 3; ++c) T[c] *= std::clamp(1.0 - s[c] / m, 0.0, 1.0);
        return T[0] + T[1] + T[2] > 0.0;
    });
    return done ? T : Vec3d(0.0);
}

Vec3d deltaTrackingTransmittance(MediumRay& ray, Rng& rng, std::int64_t& collisions) {
    Vec3d T(1.0);
    const bool done = trackCollisions(ray, rng, collisions, [&](double t, double m) {
        const Vec3d s = ray.at(t).extinction;
        const double real = std::clamp(minChannel(s) / m, 0.0, 1.0);
        if (rng.uniformDouble() < real) return T = Vec3d(0.0), false;
        for (int c = 0; c < 3; ++c) T[c] *= std::clamp(1.0 - s[c] / m, 0.0, 1.0) / (1.0 - real);
        return T[0] + T[1] + T[2] > 0.0;
    });
    return done ? T : Vec3d(0.0);
}

FreeFlight sampleFreeFlight(MediumRay& ray, Rng& rng, Vec3d& throughput, std::int64_t& collisions) {
    FreeFlight flight;
    Vec3d emitted(0.0);
    const bool done = trackCollisions(ray, rng, collisions, [&](double t, double m) {
        const MediumCoefficients c = ray.at(t);
        emitted += throughput * c.emission / m;
        Vec3d nullSigma(0.0);
        for (int k = 0; k < 3; ++k) nullSigma[k] = std::max(0.0, m - c.extinction[k]);
        const double ps = mean(abs3(throughput * c.scattering)), pn = mean(abs3(throughput * nullSigma));
        if (!(ps + pn > 0)) return throughput = Vec3d(0.0), false;  // all absorbed
        const double pScatter = ps / (ps + pn);
        if (rng.uniformDouble() < pScatter) {
            throughput *= c.scattering / (m * pScatter);
            flight = {true, t, c};
            flight.coefficients.g = ray.pickPhase(rng, throughput);
            return false;
        }
        throughput *= nullSigma / (m * (1.0 - pScatter));
        return true;
    });
    if (!done) throughput = Vec3d(0.0);
    flight.emitted = emitted;
    return flight;
}

}  // namespace weft
