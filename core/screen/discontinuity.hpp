#pragma once
// The discontinuity buffer and the discontinuity-aware separable Gaussian
// blur of Segovia et al. 2006, section 4.5. A pixel is on a discontinuity
// when any of its three "positive" neighbours (x+1, y), (x, y+1), (x+1, y+1)
// is not similar: normals apart by more than an angle, positions apart by
// more than a fraction of the depth, or one of the two is background.
// Neighbours outside the image are ignored.
//
// The blur walks away from each pixel along +x and -x (then +y and -y),
// adding Gaussian-weighted neighbours until the kernel radius or a
// discontinuity: a step from q to q+1 is allowed only when q is not on a
// discontinuity, so a pixel on one explores only the negative directions.
#include <cstdint>
#include <vector>

#include "core/screen/gbuffer.hpp"

namespace weft {

struct DiscontinuityThresholds {
    float normalCos = 0.9f;   // neighbours' normals must have a dot product of at least this
    float position = 0.05f;   // and be closer than this times the larger depth
};

bool similarTexels(const GTexel& a, const GTexel& b, const DiscontinuityThresholds& t);

// 1 where the pixel is on a discontinuity, else 0.
std::vector<std::uint8_t> discontinuityBuffer(const GBuffer& g, const DiscontinuityThresholds& t);

// Blurs the first `channels` of every `stride` floats per pixel in place;
// kernel size 2*radius+1, sigma = radius / 2 (radius 0: no-op). The pass
// along x goes to a scratch buffer of the blurred channels only, which may
// reuse a released buffer's pages (core/base/memory/large_buffer.hpp): whatever
// they held is never read.
void discontinuityBlur(float* data, int width, int height, int stride, int channels,
                       const std::vector<std::uint8_t>& discontinuity, int radius);
inline void discontinuityBlur(std::vector<float>& data, int width, int height, int channels,
                              const std::vector<std::uint8_t>& discontinuity, int radius) {
    discontinuityBlur(data.data(), width, height, channels, channels, discontinuity, radius);
}

}  // namespace weft
