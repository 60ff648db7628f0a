#pragma once
// The render target of the modelled pipeline: float RGBA colour, float
// depth (like GL_DEPTH32F) and 8-bit stencil, row-major from the bottom row.
#include <array>
#include <cstdint>
#include <vector>

namespace weft::hwsim {

struct Framebuffer {
    Framebuffer(int w, int h, float clearDepth = 1.0f)
        : width(w), height(h), color(std::size_t(w) * h, {0, 0, 0, 0}), depth(std::size_t(w) * h, clearDepth),
          stencil(std::size_t(w) * h, 0) {}
    int width, height;
    std::vector<std::array<float, 4>> color;
    std::vector<float> depth;
    std::vector<std::uint8_t> stencil;
    std::size_t index(int x, int y) const { return std::size_t(y) * width + x; }
};

}  // namespace weft::hwsim
