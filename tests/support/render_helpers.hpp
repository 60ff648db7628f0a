#pragma once
// In-process renders for tests (no files), through the same path as the CLI.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "core/image/compare/image_compare.hpp"
#include "plugins/host/render_job.hpp"

namespace weft::test {

inline RenderOutcome render(const std::string& input, const std::string& res, std::vector<std::string> sets,
                            std::string technique = "volume.raymarch", int threads = 0, std::optional<int> spp = {}) {
    RenderRequest r;
    r.input = input;
    r.resolution = parseResolution(res);
    r.sets = std::move(sets);
    r.technique = std::move(technique);
    r.threads = threads;
    r.spp = spp;
    return renderToImage(r);
}

inline double rmse(const Image& a, const Image& b) { return compareImages(a, b).overall.rmse; }

// The largest colour value (R, G, B) of an image.
inline double peakColourOf(const Image& img) {
    double m = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
            for (int c = 0; c < 3; ++c) m = std::max(m, double(img.at(x, y, c)));
    return m;
}

}  // namespace weft::test
