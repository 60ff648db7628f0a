#pragma once
// The render target of the modelled pipeline: float colour of 1 to 4
// channels (GL_R32F .. GL_RGBA32F; a replay picks what its GL counterpart
// renders to, since the colour plane's memory traffic is much of a
// replay's time), float depth (like GL_DEPTH32F) and 8-bit stencil,
// row-major from the bottom row. The planes are LargeBuffers: a 1024x1024
// target on small pages faults in thousands of times, which costs more than
// a replay's drawing.
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "core/base/memory/large_buffer.hpp"

namespace weft::hwsim {

struct Framebuffer {
    Framebuffer(int w, int h, float clearDepth = 1.0f, int colorChannels = 4)
        : width(w), height(h), channels(colorChannels), color(std::size_t(w) * h * std::size_t(colorChannels), 0.0f),
          depth(std::size_t(w) * h, clearDepth), stencil(std::size_t(w) * h, std::uint8_t(0)) {
        if (colorChannels < 1 || colorChannels > 4) throw std::invalid_argument("hwsim framebuffer: 1 to 4 colour channels");
    }
    int width, height;
    int channels;              // colour floats per pixel, 1 to 4
    LargeBuffer<float> color;  // `channels` floats per pixel
    LargeBuffer<float> depth;
    LargeBuffer<std::uint8_t> stencil;
    std::size_t index(int x, int y) const { return std::size_t(y) * width + x; }
    float* colorAt(std::size_t idx) { return &color[idx * std::size_t(channels)]; }
    const float* colorAt(std::size_t idx) const { return &color[idx * std::size_t(channels)]; }
    // A texture fetch of the pixel: channels the target lacks read as GL
    // fills them, (0, 0, 1) for green, blue and alpha.
    std::array<float, 4> texel(std::size_t idx) const {
        std::array<float, 4> t{0, 0, 0, 1};
        for (int ch = 0; ch < channels; ++ch) t[std::size_t(ch)] = colorAt(idx)[ch];
        return t;
    }
};

}  // namespace weft::hwsim
