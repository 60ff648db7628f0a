#pragma once
// The render target of the modelled pipeline: float RGBA colour, float
// depth (like GL_DEPTH32F) and 8-bit stencil, row-major from the bottom row.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace weft::hwsim {

// Asks the kernel to back [p, p + bytes) with huge pages where it can: a
// large target otherwise faults in page by page (thousands of faults for
// 1024x1024, which cost more than a replay's drawing). A hint only.
void adviseHugePages(void* p, std::size_t bytes);

struct Framebuffer {
    Framebuffer(int w, int h, float clearDepth = 1.0f) : width(w), height(h) {
        const std::size_t n = std::size_t(w) * h;
        fill(color, n, {0, 0, 0, 0});
        fill(depth, n, clearDepth);
        fill(stencil, n, std::uint8_t(0));
    }
    int width, height;
    std::vector<std::array<float, 4>> color;
    std::vector<float> depth;
    std::vector<std::uint8_t> stencil;
    std::size_t index(int x, int y) const { return std::size_t(y) * width + x; }

private:
    template <class T>
    static void fill(std::vector<T>& plane, std::size_t n, const T& value) {
        plane.reserve(n);  // not yet touched: the hint still applies
        adviseHugePages(plane.data(), n * sizeof(T));
        plane.assign(n, value);
    }
};

}  // namespace weft::hwsim
