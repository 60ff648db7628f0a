#pragma once
// What every technique that renders through the image plane
// (core/sampling/image_plane.hpp) must show: a patterned or filtered render
// is the same at any thread count, is a different image from the default,
// and converges to the same picture (the same mean, within its noise).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/error.hpp"
#include "plugins/host/render_job.hpp"

namespace weft::test {

inline Image renderPlane(const std::string& input, const std::string& technique, const std::string& res, int spp,
                         std::uint64_t seed, std::vector<std::string> sets, int threads = 0) {
    RenderRequest r;
    r.input = input, r.technique = technique, r.resolution = parseResolution(res), r.spp = spp, r.seed = seed;
    r.sets = std::move(sets), r.threads = threads;
    return renderToImage(r).image;
}

inline bool sameBits(const Image& a, const Image& b) { return a.width() == b.width() && a.data() == b.data(); }

// The mean over the interior pixels (at least `border` from the edge: a wide
// filter renormalises its weights there, which biases them) of the RGB
// difference a - b, and the standard error of that mean from the spread of
// the differences, pixels taken as independent. Both images estimate the
// same picture, so the spread is their noise, not the picture's structure.
struct MeanDifference {
    double mean = 0, stdError = 0;
};

inline MeanDifference meanDifference(const Image& a, const Image& b, int border) {
    double sum = 0, sq = 0;
    int n = 0;
    for (int y = border; y < a.height() - border; ++y)
        for (int x = border; x < a.width() - border; ++x) {
            double d = 0;
            for (int c = 0; c < 3; ++c) d += (double(a.at(x, y, c)) - b.at(x, y, c)) / 3.0;
            sum += d, sq += d * d, ++n;
        }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sq / n - mean * mean) / n)};
}

inline bool finiteImage(const Image& img) {
    for (float v : img.data())
        if (!std::isfinite(v)) return false;
    return true;
}

// The checks above for one technique on one input: `variant` is a --set
// (a pattern or a filter), rendered at spp with a fixed seed. The mean
// difference from the default must lie within five standard errors: a
// filter correlates neighbouring pixels, which can make the estimate up to
// sqrt(2) too small, so at least 3.5 true ones (a false alarm rate below
// 1e-3 were the seeds not fixed).
inline void expectImagePlaneVariant(const std::string& input, const std::string& technique, const std::string& res,
                                    int spp, std::vector<std::string> base, const std::string& variant) {
    std::vector<std::string> sets = base;
    sets.push_back(variant);
    const Image one = renderPlane(input, technique, res, spp, 7, sets, 1);
    const Image two = renderPlane(input, technique, res, spp, 7, sets, 2);
    EXPECT_TRUE(sameBits(one, two)) << variant << ": 1 and 2 threads differ";
    EXPECT_TRUE(finiteImage(one)) << variant;
    const Image plain = renderPlane(input, technique, res, spp, 7, base, 2);
    EXPECT_FALSE(sameBits(one, plain)) << variant << " renders the default image";
    const MeanDifference d = meanDifference(one, plain, 2);
    EXPECT_GT(d.stdError, 0) << variant;
    EXPECT_LT(std::abs(d.mean), 5 * d.stdError) << variant << ": mean difference " << d.mean << ", standard error " << d.stdError;
}

// A bad pattern is a one-line error that names the key.
inline void expectBadPatternNamed(const std::string& input, const std::string& technique) {
    try {
        renderPlane(input, technique, "8x8", 1, 0, {"pattern=nonsense:3"});
        ADD_FAILURE() << "pattern=nonsense:3 was accepted";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("pattern"), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

}  // namespace weft::test
