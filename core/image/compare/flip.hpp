#pragma once
// LDR-FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for
// Alternating Images"): a per-pixel perceptual difference in [0, 1] between
// a test image and a reference, as seen on a display at a given viewing
// distance (pixels per degree of visual angle). Written from the paper.
//
// Colour: sRGB -> YCxCz, CSF filtering per channel, -> CIELAB, Hunt
// adjustment, HyAB distance, power (q_c = 0.7) and the two-part remap
// (p_c = 0.4, p_t = 0.95). Features: edges and points of the achromatic
// channel (Gaussian first and second derivatives, q_f = 0.5). The two
// combine as dE = dEc^(1 - dEf). Borders are clamped to the edge.
//
// Inputs are weft's scene-linear R, G, B: they are clamped to [0, 1] and
// taken as the linear light an sRGB display shows for them (encoding to
// sRGB and FLIP's decoding are then the identity, so neither is done).
// Alpha is ignored: premultiplied colour is what shows over black.
//
// LDR-FLIP is symmetric: every step treats the images alike and compares
// them with |.| or a distance, so swapping them gives the same map.
#include <memory>

#include "core/image/image.hpp"

namespace weft {

struct FlipResult {
    double mean = 0;  // mean of errorMap
    Image errorMap;   // one channel, "FLIP", values in [0, 1]
};

// Throws Error when the sizes differ, an image lacks R, G or B, or
// pixelsPerDegree is not a positive finite number. The default, 67, is the
// paper's 0.7 m from a 24" 4K monitor.
FlipResult flipError(const Image& test, const Image& reference, double pixelsPerDegree = 67.0);

// A reference prepared once (its filtered colour and features) for many
// test images, as a sweep measures every run against one reference:
// compare(test) equals flipError(test, reference) and does half its work.
class FlipReference {
public:
    explicit FlipReference(const Image& reference, double pixelsPerDegree = 67.0);
    ~FlipReference();
    FlipResult compare(const Image& test) const;
    double meanError(const Image& test) const;  // compare(test).mean without the map

private:
    double compareInto(const Image& test, float* map) const;
    struct Side;
    int width_, height_;
    double ppd_;
    std::unique_ptr<const Side> side_;
};

}  // namespace weft
