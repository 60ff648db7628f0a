// Image regression of the built-in default scene against a committed
// reference, with the OpenImageIO testsuite's thresholds: fail when more than
// 2% of pixels differ by more than 0.004, or any pixel by more than 0.012.
// Regenerate deliberately with tests/regression/default_scene/run.sh --update.
#include <gtest/gtest.h>

#include "core/image/io/image_io.hpp"
#include "tests/support/render_helpers.hpp"

using namespace weft;

TEST(Regression, DefaultSceneMatchesReference) {
    const Image ref = readImage(std::string(WEFT_SOURCE_DIR) + "/tests/regression/default_scene/ref/cloud_128.exr");
    const Image img = test::render("builtin:cloud", "128x128", {}).image;
    const ImageComparison c = compareImages(img, ref, 0.004);
    EXPECT_LE(double(c.pixelsAbove) / double(c.pixels), 0.02) << c.pixelsAbove << " pixels above 0.004";
    EXPECT_LE(c.overall.maxAbs, 0.012);
    EXPECT_GT(ref.at(64, 64, 3), 0.5f);  // the reference is not empty
}
