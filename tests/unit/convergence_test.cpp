// volume.raymarch converges to its fine-step limit at first order: halving
// the step roughly halves the error against a render at a much finer step.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/render_helpers.hpp"

using namespace weft;

TEST(RaymarchConvergence, ErrorShrinksAtFirstOrderAsStepShrinks) {
    const char* scene = "builtin:cloud";
    const Image ref = test::render(scene, "64x64", {"step=0.03125", "ert=1"}).image;
    double previous = 0;
    std::vector<double> errors;
    for (const char* step : {"2", "1", "0.5", "0.25"}) {
        const double e = test::rmse(test::render(scene, "64x64", {std::string("step=") + step, "ert=1"}).image, ref);
        errors.push_back(e);
        if (previous > 0) {
            const double order = std::log2(previous / e);
            EXPECT_GT(order, 0.8) << "step " << step << ": error " << e << " after " << previous;
        }
        previous = e;
    }
    // Overall slope over the 8x range of steps, fitted end to end.
    const double slope = std::log2(errors.front() / errors.back()) / 3.0;
    EXPECT_GT(slope, 0.9);
    EXPECT_GT(errors.back(), 0.0);
}
