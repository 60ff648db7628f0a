#pragma once
// An image regression case: a folder holding case.json (what to render and
// the pass rule) and ref.exr (the reference). The test suite and
// `weft diff --rule case.json` read the same file, so both judge alike.
//   {"input": "scenes/combined/smoke_over_ground.json", "technique": "volume.raymarch",
//    "resolution": "96x72", "spp": 4, "set": ["step=0.5"],
//    "rule": {"threshold": 0.004, "fail_fraction": 0.02, "hard_fail": 0.012}}
// input is relative to the project root.
#include <string>
#include <vector>

#include "core/image/compare/image_compare.hpp"

namespace weft {

struct RegressionCase {
    std::string input, technique, resolution;
    int spp = 1;
    std::vector<std::string> sets;
    RegressionRule rule;
};

// Reads and checks case.json; errors name the file and the key.
RegressionCase readRegressionCase(const std::string& path);

}  // namespace weft
