#pragma once
// Scenes built in code for the mesh techniques' tests.
#include <cmath>
#include <memory>

#include "core/scene/scene.hpp"
#include "plugins/technique.hpp"

namespace weft::test {

// A closed UV sphere of `material` around the origin, every face wound so
// that its front (emitting) side looks inwards.
inline TriangleMesh insideSphere(float radius, const Material& material, int rings = 24, int segments = 48) {
    TriangleMesh m;
    m.source = "sphere";
    m.materials = {material};
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const double theta = M_PI * r / rings, phi = 2 * M_PI * s / segments;
            m.positions.emplace_back(float(radius * std::sin(theta) * std::cos(phi)), float(radius * std::cos(theta)),
                                     float(radius * std::sin(theta) * std::sin(phi)));
        }
    auto idx = [&](int r, int s) { return std::uint32_t(r * segments + (s % segments)); };
    auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        const Vec3f n = (m.positions[b] - m.positions[a]).cross(m.positions[c] - m.positions[a]);
        if (n.length() < 1e-12f) return;  // the poles' degenerate triangles
        if (n.dot(m.positions[a] + m.positions[b] + m.positions[c]) > 0) std::swap(b, c);  // face inwards
        m.indices.insert(m.indices.end(), {a, b, c});
        m.material.push_back(0);
    };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) tri(idx(r, s), idx(r + 1, s), idx(r + 1, s + 1)), tri(idx(r, s), idx(r + 1, s + 1), idx(r, s + 1));
    return m;
}

// Renders a scene built in code with a technique and parameters.
inline Image renderScene(const Scene& scene, const std::string& technique, const std::map<std::string, std::string>& params,
                         int width, int height, int spp, std::uint64_t seed = 0, RenderContext* out = nullptr) {
    const TechniqueInfo& info = techniques().get(technique);
    auto t = info.create(scene, info.params.parse(params));
    RenderContext local;
    RenderContext& ctx = out ? *out : local;
    ctx.settings.width = width, ctx.settings.height = height, ctx.settings.spp = spp, ctx.settings.seed = seed;
    return t->render(scene, ctx);
}

inline double channelMean(const Image& img, int channel) {
    double sum = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) sum += img.at(x, y, channel);
    return sum / (double(img.width()) * img.height());
}

}  // namespace weft::test
