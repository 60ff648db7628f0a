// lighting.vpl_deferred — non-interleaved deferred shading of interleaved
// sample patterns (Segovia et al. 2006) with VPLs from instant radiosity.
//
// Passes, each timed under its own name and counted:
//   VG    VPL generation: `vpls` light paths, one bounce (vpl.hpp)
//   BC    G-buffer creation with Embree ray streams (core/gbuffer)
//   BS    G-buffer split into n x m sub-buffers (`split=one_pass | two_pass`
//         with `block` p x q blocks; core/screen/interleave.hpp)
//   SSM / SNSM  shading of each sub-buffer with its own VPL subset, with
//         Embree visibility per VPL (`visibility=true`) or without
//   BG    gathering the light buffer back
//   KK    Kollig-Keller compensation of the geometry-term clamp (`clamp`,
//         `bias_compensation` rays per pixel)
//   DB    discontinuity buffer, B: discontinuity-aware separable Gaussian blur
//   C     compose: albedos applied after the blur, point/directional lights
//         (exact, every pixel), emission seen directly
//   VT    with volumes: the transmittance from the eye to every texel
// By default (`split=fused`) the shading pass reads each sub-buffer's
// texels from the G-buffer through the interleave and writes their light
// in image order: BS and BG only feed it and take from it, so they are
// fused into it (same image to the bit, two frame-sized copies fewer).
// `interleave=1x1` has no BS/BG: plain deferred shading, every VPL at every
// pixel. Each pixel of an n x m pattern sees the VPLs of paths k with
// k mod (n m) equal to its sub-buffer index.
//
// AOVs: direct.RGB, indirect.RGB, albedo.RGB, N.XYZ, Z, discontinuity,
// subbuffer. Counters: vpl.paths, vpl.emitter, vpl.bounce, rays.*,
// fragments.gbuffer, fragments.shaded (texel x VPL evaluations); with
// volumes volume.transmittance (segments marched), volume.steps,
// volume.lookups.
//
// Volumes absorb and out-scatter, never scatter in
// (core/lighting/volume_attenuation.hpp): a pixel's surface colour is
// multiplied by the transmittance from the eye, each VPL and light shadow
// ray (SSM; SNSM ignores volumes as it ignores occluders) and compensation
// ray by its own, a bounce VPL by that of the path that made it; a pixel
// that sees no surface has alpha 1 - transmittance.
#include <cstdio>
#include <optional>

#include "core/lighting/delta_lights.hpp"
#include "core/screen/discontinuity.hpp"
#include "core/screen/interleave.hpp"
#include "core/mesh/mesh_accel.hpp"
#include "plugins/lighting_vpl_deferred/shading.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

const Counter kVplPaths{"vpl.paths", "light paths traced to place VPLs"};
const Counter kVplEmitter{"vpl.emitter", "VPLs placed on emitters"};
const Counter kVplBounce{"vpl.bounce", "VPLs placed at path bounces"};
const Counter kRaysVpl{"rays.vpl", "rays traced while placing VPLs"};
const Counter kFragmentsGbuffer{"fragments.gbuffer", "G-buffer texels filled"};
const Counter kRaysShadowDelta{"rays.shadow.delta", "shadow rays towards the scene's delta lights (point, directional)"};

std::pair<int, int> parsePair(const std::string& text, int maxValue) {
    int a = 0, b = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &a, &x, &b, &extra) != 3 || x != 'x' || a < 1 || b < 1 || a > maxValue || b > maxValue)
        throw Error("expected NxM with N and M in [1, " + std::to_string(maxValue) + "], e.g. 4x4");
    return {a, b};
}

// How the G-buffer reaches the sub-buffers: read in place by the shading
// pass, or split into copies (and the light gathered back) in one pass or two.
enum class Split { Fused, OnePass, TwoPass };

Split splitNamed(const std::string& name) {
    return name == "two_pass" ? Split::TwoPass : name == "one_pass" ? Split::OnePass : Split::Fused;
}

struct VplParams {
    std::uint32_t paths;
    int n, m, p, q;
    Split split;
    bool visibility, filter;
    float clampFraction;
    double volumeStep;
    int compensation, radius;
    DiscontinuityThresholds thresholds;
    GlossyModel glossy;
};

VplParams readParams(const ParamSet& ps) {
    VplParams v;
    v.paths = std::uint32_t(ps.getInt("vpls"));
    std::tie(v.n, v.m) = parsePair(ps.getString("interleave"), 64);
    std::tie(v.p, v.q) = parsePair(ps.getString("block"), 4096);
    if (!ps.wasSet("block")) v.p = (v.p + v.n - 1) / v.n * v.n, v.q = (v.q + v.m - 1) / v.m * v.m;  // default: 16x16 rounded up to the pattern
    v.split = splitNamed(ps.getString("split"));
    v.visibility = ps.getBool("visibility");
    v.filter = ps.getBool("filter");
    v.clampFraction = float(ps.getFloat("clamp"));
    v.volumeStep = ps.getFloat("volume_step");
    v.compensation = int(ps.getInt("bias_compensation"));
    const int kernel = int(ps.getInt("kernel"));
    v.radius = kernel > 0 ? kernel / 2 : std::max(v.n, v.m);  // auto: sigma of half a pattern period
    v.thresholds.normalCos = float(std::cos(ps.getFloat("normal_threshold") * M_PI / 180.0));
    v.thresholds.position = float(ps.getFloat("position_threshold"));
    v.glossy = Brdf::modelNamed(ps.getString("glossy"));
    if (v.split == Split::TwoPass && (v.p % v.n || v.q % v.m))
        throw Error("lighting.vpl_deferred: block=" + ps.getString("block") + " must be a multiple of interleave=" + ps.getString("interleave") + " in each direction");
    if (v.paths < std::uint32_t(v.n * v.m))
        throw Error("lighting.vpl_deferred: vpls=" + std::to_string(v.paths) + " leaves some of the " + std::to_string(v.n * v.m) + " sub-buffers without VPLs");
    return v;
}

class VplDeferred final : public Technique {
public:
    VplDeferred(const Scene& scene, const ParamSet& ps) : p_(readParams(ps)) {
        requireMeshLights(scene, "lighting.vpl_deferred");
    }

    Image render(const Scene& scene, RenderContext& ctx) override {
        const RenderSettings& s = ctx.settings;
        if (s.spp != 1)
            throw Error("lighting.vpl_deferred shades one G-buffer sample per pixel (spp " + std::to_string(s.spp) +
                        " given); raise 'vpls' for quality, or average frames rendered with different seeds");
        std::vector<Brdf> brdfs;
        for (const Material& m : scene.materials) brdfs.push_back(Brdf::of(m, p_.glossy));
        const VolumeAttenuation volumes(scene, p_.volumeStep);
        ShadeConfig cfg = shadeConfig(scene);
        if (volumes.active()) cfg.volumes = &volumes;
        { ScopedTimer t(ctx.timings, "build_bvh"); scene.accel(); scene.emitters(); }

        VplSet vpls;
        { ScopedTimer t(ctx.timings, "VG.vpls"); vpls = generateVpls(scene, p_.paths, s.seed, volumes, ctx.counters); }
        ctx.counters.add(kVplPaths, vpls.paths), ctx.counters.add(kVplEmitter, vpls.emitterCount);
        ctx.counters.add(kVplBounce, vpls.bounceCount), ctx.counters.add(kRaysVpl, vpls.rays);

        GBuffer g;
        { ScopedTimer t(ctx.timings, "BC.gbuffer"); g = createGBuffer(scene, s, ctx.counters); }
        ctx.counters.add(kFragmentsGbuffer, std::int64_t(g.texels.size()));
        std::vector<Vec3f> eyeT;
        if (volumes.active()) {
            ScopedTimer t(ctx.timings, "VT.transmittance");
            eyeT = cameraTransmittance(scene, g, volumes, ctx.counters);
        }

        const SubBufferLayout layout(s.width, s.height, p_.n, p_.m);
        const bool copies = p_.split != Split::Fused && layout.count() > 1;
        LargeBuffer<ShadeTexel> split;
        if (copies) split = splitPass(g, layout, ctx);
        LightBuffer light;
        {
            ScopedTimer t(ctx.timings, p_.visibility ? "SSM.shade" : "SNSM.shade");
            light = shadeSubBuffers(scene, {copies ? &split : nullptr, &g}, layout, vpls, brdfs, cfg, ctx.counters, s.monitor);
        }
        LargeBuffer<ShadeTexel>().swap(split);  // read by no later pass
        if (copies) gatherPass(light, layout, ctx);
        if (p_.compensation > 0 && std::isfinite(cfg.gmax)) {
            ScopedTimer t(ctx.timings, "KK.bias_compensation");
            compensateClamping(scene, g, brdfs, cfg, p_.compensation, s.seed, light, ctx.counters);
        }
        std::vector<std::uint8_t> disc;
        { ScopedTimer t(ctx.timings, "DB.discontinuity"); disc = discontinuityBuffer(g, p_.thresholds); }
        if (p_.filter && layout.count() > 1) blurPass(light, disc, brdfs, layout, ctx);
        ScopedTimer t(ctx.timings, "C.compose");
        return compose(scene, g, light, disc, eyeT, layout, brdfs, cfg, ctx.counters);
    }

private:
    ShadeConfig shadeConfig(const Scene& scene) const {
        ShadeConfig cfg;
        cfg.visibility = p_.visibility, cfg.eps = rayEpsilon(scene);
        const Vec3d eye = scene.camera.eye;
        cfg.eye = Vec3f(float(eye.x()), float(eye.y()), float(eye.z()));
        const float clampDistance = p_.clampFraction * float(scene.worldBox().extents().length());
        cfg.gmax = p_.clampFraction > 0 ? 1.0f / (clampDistance * clampDistance) : std::numeric_limits<float>::infinity();
        return cfg;
    }

    // BS: the shading inputs in sub-buffer order.
    LargeBuffer<ShadeTexel> splitPass(const GBuffer& g, const SubBufferLayout& layout, RenderContext& ctx) const {
        ScopedTimer t(ctx.timings, "BS.split");
        LargeBuffer<ShadeTexel> split, scratch;
        auto pack = [](const GTexel& texel) { return ShadeTexel(texel); };
        if (p_.split == Split::TwoPass) splitTwoPass(g.texels, split, scratch, layout, p_.p, p_.q, pack);
        else splitOnePass(g.texels, split, layout, pack);
        return split;
    }

    // BG: the light buffer back in image order.
    void gatherPass(LightBuffer& light, const SubBufferLayout& layout, RenderContext& ctx) const {
        ScopedTimer t(ctx.timings, "BG.gather");
        LightBuffer gathered, scratch;
        if (p_.split == Split::TwoPass) gatherTwoPass(light, gathered, scratch, layout, p_.p, p_.q);
        else gatherOnePass(light, gathered, layout);
        std::swap(light, gathered);
    }

    // B: discontinuity-aware blur of the light factors (glossy ones only when some material is glossy).
    // Its scratch holds the blurred channels only and may reuse a released buffer's pages (core/base/memory/large_buffer.hpp).
    void blurPass(LightBuffer& light, const std::vector<std::uint8_t>& disc, const std::vector<Brdf>& brdfs,
                  const SubBufferLayout& layout, RenderContext& ctx) const {
        ScopedTimer t(ctx.timings, "B.blur");
        bool glossy = false;
        for (const Brdf& b : brdfs) glossy |= b.glossy();
        discontinuityBlur(reinterpret_cast<float*>(light.data()), layout.width(), layout.height(), kLightChannels,
                          glossy ? kLightChannels : kDiffuseChannels, disc, p_.radius);
    }

    Image compose(const Scene& scene, const GBuffer& g, const LightBuffer& light,
                  const std::vector<std::uint8_t>& disc, const std::vector<Vec3f>& eyeT, const SubBufferLayout& layout,
                  const std::vector<Brdf>& brdfs, const ShadeConfig& cfg, Counters& counters) const {
        Image img(g.width, g.height, {"R", "G", "B", "A", "direct.R", "direct.G", "direct.B", "indirect.R", "indirect.G",
                                      "indirect.B", "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z",
                                      "discontinuity", "subbuffer"});
        tbb::parallel_for(0, g.height, [&](int y) {
            enableFastFloatMode();
            std::int64_t rays = 0;
            std::optional<SegmentAttenuation> attenuation;
            if (cfg.volumes) attenuation.emplace(*cfg.volumes);
            SegmentAttenuation* media = attenuation ? &*attenuation : nullptr;
            for (int x = 0; x < g.width; ++x) {
                const GTexel& t = g.at(x, y);
                float* px = img.pixel(x, y);
                const std::size_t i = std::size_t(y) * g.width + x;
                px[17] = float(disc[i]), px[18] = float(layout.index(x, y));
                if (t.background()) {
                    if (media) px[3] = backgroundAlpha(eyeT[i]);
                    continue;
                }
                const Brdf& f = brdfs[std::size_t(t.material)];
                const LightTexel& l = light[i];
                Vec3f dd(0, 0, 0), ds(0, 0, 0);
                if (!scene.lights.empty()) directLightAt(scene, t, (cfg.eye - t.position).unitSafe(), f, cfg.eps, nullptr, false, dd, ds, rays, media);
                Vec3f direct = f.kd * (l.directD + dd) + f.ks * (l.directS + ds);
                const Material& mat = scene.materials[std::size_t(t.material)];
                if (t.front && mat.emissive()) direct += mat.emission;
                Vec3f indirect = f.kd * l.indirectD + f.ks * l.indirectS;
                if (media) direct *= eyeT[i], indirect *= eyeT[i];
                const Vec3f rgb = direct + indirect;
                const float values[17] = {rgb.x(), rgb.y(), rgb.z(), 1.0f, direct.x(), direct.y(), direct.z(),
                                          indirect.x(), indirect.y(), indirect.z(), t.albedo.x(), t.albedo.y(), t.albedo.z(),
                                          t.normal.x(), t.normal.y(), t.normal.z(), t.depth};
                std::copy(values, values + 17, px);
            }
            counters.add(kRaysShadowDelta, rays);
            if (media) media->report(counters);
        });
        return img;
    }

    VplParams p_;
};

void checkPair(const std::string& text) { parsePair(text, 4096); }

const TechniqueRegistrar registrar{{
    "lighting.vpl_deferred",
    "VPL lighting by deferred shading of interleaved sub-buffers (Segovia et al. 2006) with clamp compensation",
    ParamTable("lighting.vpl_deferred",
               {intParam("vpls", 480, 1, 1 << 22, "light paths; each leaves a VPL on the light and one where it first lands"),
                stringParam("interleave", "4x4", "interleaving pattern n x m (1x1: plain deferred shading, every VPL at every pixel)", checkPair),
                enumParam("split", "fused", {"fused", "one_pass", "two_pass"},
                          "sub-buffers: read and written through the interleave by the shading pass (fused, no copies), or split and gathered "
                          "by copies around it (BS and BG passes): texel by texel, or block split then block translation"),
                stringParam("block", "16x16", "block size p x q of the two-pass split (multiples of n and m; by default rounded up to them)", checkPair),
                boolParam("visibility", true, "shadow rays per VPL and texel (SSM); false ignores visibility (SNSM)"),
                floatParam("clamp", 0.05, 0, 10, "bounce VPLs' geometry term is clamped at 1/(clamp*scene diagonal)^2; 0 = no clamp"),
                intParam("bias_compensation", 1, 0, 256, "rays per pixel restoring the clamped energy (Kollig-Keller); 0 = off"),
                boolParam("filter", true, "discontinuity-aware Gaussian blur of the gathered light (interleaved patterns only)"),
                intParam("kernel", 0, 0, 63, "Gaussian kernel size in pixels (sigma = radius / 2); 0: 2 max(n, m) + 1, wide enough to hide the pattern"),
                floatParam("normal_threshold", 25, 0, 180, "discontinuity where neighbours' normals differ by more than this (degrees)"),
                floatParam("position_threshold", 0.05, 0, 1e6, "discontinuity where neighbours are farther apart than this times their depth"),
                enumParam("glossy", "phong", {"phong", "blinn"}, "glossy lobe of Ks/Ns materials: Phong (mirror direction) or Blinn-Phong (half vector)"),
                volumeStepParam()}),
    [](const Scene& scene, const ParamSet& p) { return std::make_unique<VplDeferred>(scene, p); },
    /*motionBlur=*/false,
    /*renders=*/Content::VolumesAndMeshes,
    /*bytesPerPixel=*/256,  // G-buffer, light, AOVs: 173 measured fused, 253 with split=one_pass copies
    /*reference=*/{"mesh.pathtrace", {}, 4096},
    /*knobs=*/{{"vpls", {"64", "256", "1024", "4096"}}, {"interleave", {"8x8", "4x4", "1x1"}}},
}};

}  // namespace

}  // namespace weft
