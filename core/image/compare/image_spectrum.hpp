#pragma once
// Power spectra of images and a measure of coherent aliasing: the strongest
// peak of an error image's power spectrum away from DC relative to the mean
// power there. Noise-like error (stochastic sampling) spreads its energy
// evenly and scores near the maximum of that many exponential variables
// (about ln(W H)); aliasing from regular sampling concentrates it in a few
// frequencies and scores far higher.
#include <vector>

namespace weft {

// |DFT|^2 of a W x H real image (row-major), frequencies 0..W-1 by 0..H-1.
// A direct separable DFT: O(W H (W + H)), deterministic, any size.
std::vector<double> powerSpectrum(const std::vector<double>& image, int W, int H);

struct AliasingPeak {
    double ratio = 0;  // peak power / mean power, over frequencies with |f| > excludeRadius
    int fx = 0, fy = 0;  // where the peak is (signed, cycles per image)
};
AliasingPeak coherentAliasing(const std::vector<double>& error, int W, int H, double excludeRadius = 2);

// RMS of an image (an error image) after a Gaussian blur of the given sigma
// in pixels (edges clamped): the error seen from a distance, where noise
// averages away and low-frequency structures (aliasing, banding) remain.
double blurredRms(const std::vector<double>& image, int W, int H, double sigma);

}  // namespace weft
