#pragma once
// Virtual point lights by instant radiosity (Keller 1997), one bounce: each
// light path starts on a light (picked by power) and leaves two VPLs: one on
// the emitter itself (direct light from area lights) and one where its first
// ray lands (indirect light). Path k belongs to sub-buffer subset k mod S.
#include <cstdint>
#include <vector>

#include "core/base/run/counters.hpp"
#include "core/lighting/brdf.hpp"
#include "core/lighting/volume_attenuation.hpp"
#include "core/screen/gbuffer.hpp"
#include "core/scene/scene.hpp"

namespace weft {

enum class VplKind : std::uint8_t { Emitter, Bounce };

struct Vpl {
    Vec3f position;
    Vec3f normal;   // emitter: the emitting side; bounce: the side the light arrived on
    Vec3f weight;   // emitter: Ke / pdf; bounce: path throughput (flux x paths)
    Vec3f wi;       // bounce: unit direction back to where the light came from
    std::int32_t material = -1;
    VplKind kind = VplKind::Emitter;
    std::uint32_t path = 0;
};

struct VplSet {
    std::vector<Vpl> vpls;  // ordered by path
    std::uint32_t paths = 0;
    std::int64_t emitterCount = 0, bounceCount = 0;
    std::int64_t rays = 0;
};

// With active volumes a bounce VPL's weight carries the transmittance of
// the segment from the light to it.
VplSet generateVpls(const Scene& scene, std::uint32_t paths, std::uint64_t seed, const VolumeAttenuation& volumes,
                    Counters& counters);

// Lights a G-buffer texel with one VPL: adds to the diffuse factor D (to be
// multiplied by Kd) and glossy factor S (by Ks). gmax bounds the geometry
// term of bounce VPLs (infinity: no clamping). Returns false when the VPL
// cannot reach the texel (facing away), in which case no shadow ray is needed.
struct VplShading {
    Vec3f d, s;
    Vec3f toLight;  // unit, from the texel to the VPL
    float distance;
};
bool shadeWithVpl(const Vpl& vpl, const ShadeTexel& texel, const Vec3f& eye, const std::vector<Brdf>& brdfs, float gmax, VplShading& out);

}  // namespace weft
