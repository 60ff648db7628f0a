#pragma once
// The render target of the modelled pipeline: float RGBA colour, float
// depth (like GL_DEPTH32F) and 8-bit stencil, row-major from the bottom row.
// The planes are LargeBuffers: a 1024x1024 target on small pages faults in
// thousands of times, which costs more than a replay's drawing.
#include <array>
#include <cstddef>
#include <cstdint>

#include "core/base/large_buffer.hpp"

namespace weft::hwsim {

struct Framebuffer {
    Framebuffer(int w, int h, float clearDepth = 1.0f)
        : width(w), height(h), color(std::size_t(w) * h, {0, 0, 0, 0}), depth(std::size_t(w) * h, clearDepth),
          stencil(std::size_t(w) * h, std::uint8_t(0)) {}
    int width, height;
    LargeBuffer<std::array<float, 4>> color;
    LargeBuffer<float> depth;
    LargeBuffer<std::uint8_t> stencil;
    std::size_t index(int x, int y) const { return std::size_t(y) * width + x; }
};

}  // namespace weft::hwsim
