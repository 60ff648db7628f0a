#pragma once
// The shading passes of interleaved deferred shading: every sub-buffer of
// the G-buffer is lit by its own VPL subset (SSM: with an Embree
// shadow ray per VPL and texel, shot as one coherent stream from the VPL to
// a run of the sub-buffer's texels; SNSM: visibility ignored), and the
// Kollig-Keller pass that restores the energy the geometry-term clamp
// removes.
#include <cstdint>
#include <type_traits>
#include <vector>

#include "core/base/run/counters.hpp"
#include "core/base/run/render_monitor.hpp"
#include "core/base/memory/large_buffer.hpp"
#include "core/screen/gbuffer.hpp"
#include "core/screen/interleave.hpp"
#include "plugins/lighting_vpl_deferred/vpl.hpp"

namespace weft {

// Per pixel light before the albedos are applied (blurred as a whole). The
// diffuse factors come first, so scenes without glossy materials blur only
// the first kDiffuseChannels floats.
// Trivial, so a frame of them comes zeroed by the kernel (zeroedBuffer) and
// a gather writes into one without clearing it first.
struct LightTexel {
    Vec3f directD, indirectD, directS, indirectS;
};
constexpr int kLightChannels = 12;
constexpr int kDiffuseChannels = 6;
static_assert(sizeof(LightTexel) == kLightChannels * sizeof(float));
static_assert(std::is_trivially_default_constructible_v<LightTexel>);
using LightBuffer = FreshBuffer<LightTexel>;

struct ShadeConfig {
    bool visibility = true;
    float gmax = 0;  // clamp of bounce VPLs' geometry term
    float eps = 1e-5f;
    Vec3f eye;
    // Active volumes attenuate the VPL shadow rays (with visibility only),
    // the direct light and the compensation rays; null in a mesh scene.
    const VolumeAttenuation* volumes = nullptr;
};

// Where the shading pass reads its texels and writes their light: the
// split copy of the G-buffer (split order; the BS and BG passes around it
// move the texels there and back), or, fused, the G-buffer itself, read and
// written in image order through the interleave (no copies). Both give the
// same light to the bit.
struct ShadeSource {
    const LargeBuffer<ShadeTexel>* split = nullptr;
    const GBuffer* gbuffer = nullptr;  // read when `split` is null
};

// The light of every texel, at the texel's index in `source`; the tasks'
// progress goes to `monitor` (which may stop the pass).
LightBuffer shadeSubBuffers(const Scene& scene, const ShadeSource& source, const SubBufferLayout& layout,
                            const VplSet& vpls, const std::vector<Brdf>& brdfs, const ShadeConfig& config,
                            Counters& counters, RenderMonitor* monitor = nullptr);

// Adds the clamped-away part of one-bounce indirect light (Kollig and Keller
// 2004): a BRDF-sampled ray from each texel; where it lands closer than the
// clamp allows (G > gmax), the direct light reflected there, weighted by
// 1 - gmax / G. `samples` rays per pixel.
void compensateClamping(const Scene& scene, const GBuffer& g, const std::vector<Brdf>& brdfs, const ShadeConfig& config,
                        int samples, std::uint64_t seed, LightBuffer& light, Counters& counters);

// Direct light from a texel's point of view: one emitter sample (if any)
// plus every point/directional light, with shadow rays (through the volumes
// when `media` is given); as D and S factors.
void directLightAt(const Scene& scene, const GTexel& t, const Vec3f& wo, const Brdf& brdf, float eps, const float* u,
                   bool emitters, Vec3f& d, Vec3f& s, std::int64_t& rays, SegmentAttenuation* media = nullptr);

}  // namespace weft
