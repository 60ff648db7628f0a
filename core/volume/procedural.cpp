// Procedural grids for the built-in scenes and for tests with known answers.
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>

#include "core/base/error.hpp"
#include "core/base/rng.hpp"
#include "core/volume/volume.hpp"

namespace weft {

namespace {

// Smooth value noise on an integer lattice, hashed from the seed.
double latticeValue(std::uint64_t seed, int x, int y, int z) {
    std::uint64_t h = hashCombine(seed, static_cast<std::uint32_t>(x));
    h = hashCombine(h, static_cast<std::uint32_t>(y));
    h = hashCombine(h, static_cast<std::uint32_t>(z));
    return toUnitFloat(h) * 2.0 - 1.0;
}

double smooth(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

double valueNoise(std::uint64_t seed, double x, double y, double z) {
    const int ix = int(std::floor(x)), iy = int(std::floor(y)), iz = int(std::floor(z));
    const double fx = smooth(x - ix), fy = smooth(y - iy), fz = smooth(z - iz);
    double v[2][2][2];
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) v[k][j][i] = latticeValue(seed, ix + i, iy + j, iz + k);
    auto lerp = [](double a, double b, double t) { return a + t * (b - a); };
    const double x00 = lerp(v[0][0][0], v[0][0][1], fx), x10 = lerp(v[0][1][0], v[0][1][1], fx);
    const double x01 = lerp(v[1][0][0], v[1][0][1], fx), x11 = lerp(v[1][1][0], v[1][1][1], fx);
    return lerp(lerp(x00, x10, fy), lerp(x01, x11, fy), fz);
}

double fbm(std::uint64_t seed, Vec3d p) {
    double sum = 0, amp = 0.5;
    for (int octave = 0; octave < 5; ++octave, p *= 2.03, amp *= 0.5)
        sum += amp * valueNoise(seed + octave, p.x(), p.y(), p.z());
    return sum;
}

// Density at a point of the unit cube for each kind.
double sphereDensity(const Vec3d& p) { return p.length() <= 0.4 ? 1.0 : 0.0; }

double cloudDensity(std::uint64_t seed, const Vec3d& p) {
    const double n = fbm(seed, p * 4.0 + Vec3d(11.5, 3.25, 7.75));
    const double shell = 0.36 + 0.12 * n - p.length();  // displaced sphere
    if (shell <= 0) return 0.0;
    const double detail = 0.5 + 0.5 * fbm(seed + 17, p * 9.0);
    return std::clamp(shell * 9.0, 0.0, 1.0) * std::clamp(detail * 1.6 - 0.15, 0.0, 1.0);
}

// A CT-like phantom in normalised attenuation: soft tissue (an ellipsoid,
// 0.3, with faint texture), a denser vessel wall around an empty lumen along
// x (where a stent tube can run), and a bone-like shell (1.0) on one side.
double ctDensity(std::uint64_t seed, const Vec3d& p) {
    const double body = (p.x() * p.x()) / 0.20 + (p.y() * p.y()) / 0.09 + (p.z() * p.z()) / 0.12;
    if (body > 1.0) return 0.0;
    const double radial = std::sqrt(p.y() * p.y() + p.z() * p.z());
    if (radial < 0.05) return 0.02;                        // lumen: blood, nearly clear
    if (radial < 0.08) return 0.6;                         // vessel wall
    const Vec3d b = p - Vec3d(0.0, -0.12, 0.05);
    const double bone = std::abs(b.length() - 0.11);
    if (bone < 0.025) return 1.0;                          // cortical shell
    return 0.3 * (0.85 + 0.15 * fbm(seed, p * 12.0));    // soft tissue
}

// A flame rising along +y from the bottom of the cube: a noisy cone of
// heat (0..1) whose soot (density) thickens into smoke above it.
double flameHeat(std::uint64_t seed, const Vec3d& p) {
    const double h = p.y() + 0.5;  // 0 at the bottom, 1 at the top
    const double n = fbm(seed + 5, Vec3d(p.x() * 6.0, p.y() * 2.5 - 1.7, p.z() * 6.0));  // tongues: stretched along y
    const double radius = 0.2 * (1.0 - 0.8 * h) + 0.14 * n, r = std::hypot(p.x(), p.z());
    if (h > 0.85 || r >= radius) return 0.0;
    const double flicker = 0.7 + 0.6 * fbm(seed + 6, p * 9.0);
    return std::clamp((1.0 - r / radius) * (1.0 - h / 0.85) * 1.6 * flicker, 0.0, 1.0);
}

double fireDensity(std::uint64_t seed, const Vec3d& p) {
    const double h = p.y() + 0.5;
    const double n = std::clamp(0.5 + 0.9 * fbm(seed + 9, p * 6.0), 0.0, 1.0);
    const double radius = 0.12 + 0.2 * h + 0.12 * fbm(seed + 10, p * 3.0), r = std::hypot(p.x(), p.z());
    const double smoke = r < radius ? std::clamp((h - 0.3) * 2.0, 0.0, 1.0) * (1.0 - r / radius) * n : 0.0;
    return std::max(smoke, 0.15 * flameHeat(seed, p));  // a thin soot in the flame itself
}

template <class Field>
openvdb::FloatGrid::Ptr sampleGrid(const std::string& name, int res, const Field& field) {
    if (res < 4 || res > 1024) throw Error("procedural volume resolution " + std::to_string(res) + " is outside [4, 1024]");
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName(name);
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    const double voxel = 1.0 / res;
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
    auto acc = grid->getAccessor();
    const int half = res / 2;
    for (int z = -half; z < half; ++z)
        for (int y = -half; y < half; ++y)
            for (int x = -half; x < half; ++x) {
                const double d = field(Vec3d(x * voxel, y * voxel, z * voxel));
                if (d > 0) acc.setValue(openvdb::Coord(x, y, z), float(d));
            }
    return grid;
}

}  // namespace

const char* proceduralKinds() { return "sphere|cloud|ct|fire"; }

openvdb::FloatGrid::Ptr makeProceduralGrid(const std::string& kind, int res, std::uint64_t seed) {
    initVdb();
    if (kind == "sphere") return sampleGrid("density", res, [](const Vec3d& p) { return sphereDensity(p); });
    if (kind == "cloud") return sampleGrid("density", res, [&](const Vec3d& p) { return cloudDensity(seed, p); });
    if (kind == "ct") return sampleGrid("density", res, [&](const Vec3d& p) { return ctDensity(seed, p); });
    if (kind == "fire") return sampleGrid("density", res, [&](const Vec3d& p) { return fireDensity(seed, p); });
    throw Error("unknown procedural volume '" + kind + "' (known: " + proceduralKinds() + ")");
}

openvdb::FloatGrid::Ptr makeProceduralTemperature(int res, std::uint64_t seed) {
    initVdb();
    return sampleGrid("temperature", res, [&](const Vec3d& p) {
        const double heat = flameHeat(seed, p);
        return heat > 0 ? 700.0 + 1300.0 * heat : 0.0;  // Kelvin: a dull red rim to a yellow-white core
    });
}

}  // namespace weft
