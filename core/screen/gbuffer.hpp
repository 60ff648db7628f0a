#pragma once
// G-buffer: what deferred shading needs of the first surface behind every
// pixel (one ray through the pixel centre, the image plane's camera sample
// at 1 spp), created with Embree ray packets, one coherent 16-ray packet per
// 4x4 pixel tile.
#include <cstdint>
#include <vector>

#include "core/base/run/counters.hpp"
#include "core/base/memory/large_buffer.hpp"
#include "core/base/run/render_context.hpp"
#include "core/scene/scene.hpp"

namespace weft {

struct GTexel {
    Vec3f position{0, 0, 0};
    Vec3f normal{0, 0, 0};  // unit, facing the camera
    Vec3f albedo{0, 0, 0};  // diffuse albedo (Kd after energy scaling)
    float depth = 0;        // distance from the eye; 0 for background
    std::int32_t material = -1;  // -1: background (nothing hit)
    bool front = false;          // the camera sees the winding side (emission side)

    bool background() const { return material < 0; }
};

// What the shading passes read of a texel, 32 bytes: the split moves these,
// not the whole texel.
struct ShadeTexel {
    Vec3f position{0, 0, 0};
    Vec3f normal{0, 0, 0};
    std::int32_t material = -1;
    float pad = 0;

    ShadeTexel() = default;
    ShadeTexel(const GTexel& t) : position(t.position), normal(t.normal), material(t.material) {}
    bool background() const { return material < 0; }
};

struct GBuffer {
    int width = 0, height = 0;
    LargeBuffer<GTexel> texels;

    GTexel& at(int x, int y) { return texels[std::size_t(y) * width + x]; }
    const GTexel& at(int x, int y) const { return texels[std::size_t(y) * width + x]; }
};

// Primary rays through pixel centres; counts rays.camera.
GBuffer createGBuffer(const Scene& scene, const RenderSettings& settings, Counters& counters);

// The normals and positions of a G-buffer as the planes the A-Trous filter
// and the sample budget are guided by (core/screen/atrous.hpp).
struct GeometryGuides;
GeometryGuides guidesOf(const GBuffer& g);

}  // namespace weft
