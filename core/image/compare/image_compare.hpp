#pragma once
// Error metrics between two images of the same size, per channel and over
// all compared channels:
//   RMSE    sqrt(mean (a-b)^2)
//   relMSE  mean (a-b)^2 / (b^2 + 0.01)   (b is the reference)
//   PSNR    10 log10(1 / MSE), peak 1 (scene-linear, so it can exceed any
//           display range; +inf for identical images)
//   SSIM    mean structural similarity (Wang et al. 2004): 8x8 windows with
//           stride 4, C1 = 0.01^2, C2 = 0.03^2 for a unit dynamic range
//   maxAbs  largest |a-b|
// Plus the OpenImageIO testsuite's per-pixel verdict counts.
#include <string>
#include <vector>

#include "core/image/image.hpp"

namespace weft {

struct ChannelError {
    std::string channel;
    double rmse = 0, relMse = 0, psnr = 0, ssim = 1, maxAbs = 0;
};

struct ImageComparison {
    std::vector<ChannelError> channels;  // in the reference's channel order
    ChannelError overall;                // channel = "all"
    long long pixelsAbove = 0;           // pixels with some channel error above `threshold`
    long long pixels = 0;
};

// Compares the channels both images have (by name). Throws when the sizes
// differ or they share no channel. threshold: the per-pixel failure level.
ImageComparison compareImages(const Image& test, const Image& reference, double threshold = 0.004);

// The pass rule of an image regression (OpenImageIO's testsuite): fail when
// more than failFraction of the pixels differ by more than threshold, or any
// pixel by more than hardFail. Stored beside each reference, so the test and
// its run script (weft diff --rule) judge alike.
struct RegressionRule {
    double threshold = 0.004;
    double failFraction = 0.02;
    double hardFail = 0.012;
};
// Empty when the comparison passes, else why it fails, in one line.
std::string regressionVerdict(const ImageComparison& c, const RegressionRule& rule);

}  // namespace weft
