#pragma once
// Camera rays in a volume's index space (unit = one voxel), clipped to the
// region where the grid can be non-zero, and front-to-back compositing of
// the emission-absorption model.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "core/scene/camera.hpp"
#include "core/volume/optics/transfer_function.hpp"
#include "core/volume/volume.hpp"

namespace weft {

struct IndexRay {
    Vec3d origin;  // index space
    Vec3d dir;     // index space, unit length: t counts voxels
    double t0 = 0, t1 = 0;  // entry and exit of the volume's index box
    double speed = 1;       // index units per unit of the world ray's parameter
    Vec3d at(double t) const { return origin + dir * t; }
};

// A stretch [lo, hi] of a ray's parameter: where a volume is occupied.
struct RayInterval {
    double lo = 0, hi = 0;
};

// Sorts the intervals of several volumes by start and joins those that
// overlap or touch, so a march visits each stretch once.
void mergeIntervals(std::vector<RayInterval>& intervals);

// Clips a world ray to the volume's index box; nothing when it misses.
std::optional<IndexRay> toIndexRay(const Ray& worldRay, const Volume& volume);

// [t0, t1] of the ray origin + t dir (index space) inside `box`; nothing when it misses.
std::optional<std::pair<double, double>> clipToBox(const Vec3d& origin, const Vec3d& dir, const openvdb::CoordBBox& box);

// World directions in a volume's index space through its transform's linear
// part (weft reads linear transforms only): what worldToIndex(o + d) -
// worldToIndex(o) gives, up to rounding, without two map calls a ray.
class IndexDirections {
public:
    explicit IndexDirections(const Volume& volume);
    Vec3d operator()(const Vec3d& world) const { return column_[0] * world.x() + column_[1] * world.y() + column_[2] * world.z(); }

private:
    Vec3d column_[3];
};

// Premultiplied colour and transmittance of one ray, front to back.
struct RayAccumulator {
    float r = 0, g = 0, b = 0;
    float transmittance = 1;

    // A segment of opacity alpha emitting colour c per unit opacity.
    void add(const TfSample& c, float alpha) {
        const float w = transmittance * alpha;
        r += w * c.r, g += w * c.g, b += w * c.b;
        transmittance *= 1.0f - alpha;
    }
    // A pre-integrated segment: opacity-weighted colour (r, g, b) and opacity a.
    void addPremultiplied(float sr, float sg, float sb, float a) {
        r += transmittance * sr, g += transmittance * sg, b += transmittance * sb;
        transmittance *= 1.0f - a;
    }
    float opacity() const { return 1.0f - transmittance; }
};

// 1 - exp(-t) for t >= 0, within 2 ulp of the exact value and with full
// relative precision near 0 (as -expm1f(-t)), inline: the ray marcher takes
// one per sample, and the C library's expm1f call took 9.5 ns of a loop
// where this takes 4.5. t = k ln2 + r with |r| <= ln2 / 2, so 1 - exp(-t) =
// (1 - 2^-k) + 2^-k (1 - exp(-r)), the last factor by its Taylor series to
// r^7 (truncation below 2e-8 relative). NaN stays NaN; from t = 87 on
// (exp(-t) below float's normal range) the opacity is 1.
inline float opacityOfDepth(float t) {
    if (!(t < 87.0f)) return t != t ? t : 1.0f;
    // Rounded to the nearest integer by adding and taking away 1.5 * 2^23 (no library call).
    const float k = (t * 1.44269504f + 12582912.0f) - 12582912.0f;
    const float r = (t - k * 0.693145751953125f) - k * 1.42860677e-06f;  // ln 2 in two parts: k ln2_hi is exact
    // 1 - exp(-r) = r - r^2/2 + r^3/6 - ... - r^7 / 5040 (alternating: exact at r = 0, no cancellation).
    const float series =
        r * (1.0f - r * (0.5f - r * (1.0f / 6 - r * (1.0f / 24 - r * (1.0f / 120 - r * (1.0f / 720 - r * (1.0f / 5040)))))));
    if (k == 0.0f) return series;
    const float scale = std::bit_cast<float>(std::uint32_t(127 - int(k)) << 23);  // 2^-k, normal for 1 <= k <= 126
    return (1.0f - scale) + scale * series;
}

// Opacity of a segment of `length` voxels at constant extinction; stays in
// [0, 1] for any extinction, including huge ones.
inline float segmentOpacity(float extinction, float length) {
    return opacityOfDepth(std::max(extinction, 0.0f) * length);
}

}  // namespace weft
