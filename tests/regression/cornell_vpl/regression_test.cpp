// Image regression of lighting.vpl_deferred on the small Cornell box (4x4
// interleaving, 480 VPL paths, filtered) against a committed reference, with
// the OpenImageIO testsuite's thresholds: fail when more than 2% of pixels
// differ by more than 0.004, or any pixel by more than 0.012. Regenerate
// deliberately with tests/regression/cornell_vpl/run.sh --update.
#include <gtest/gtest.h>

#include "core/image/io/image_io.hpp"
#include "tests/support/render_helpers.hpp"

using namespace weft;

TEST(Regression, CornellVplMatchesReference) {
    const Image ref = readImage(std::string(WEFT_SOURCE_DIR) + "/tests/regression/cornell_vpl/ref/cornell_vpl_64.exr");
    const Image img = test::render(std::string(WEFT_SOURCE_DIR) + "/scenes/cornell.json", "64x64", {}, "lighting.vpl_deferred").image;
    ASSERT_EQ(img.channelCount(), ref.channelCount());
    const ImageComparison c = compareImages(img, ref, 0.004);
    EXPECT_LE(double(c.pixelsAbove) / double(c.pixels), 0.02) << c.pixelsAbove << " pixels above 0.004";
    EXPECT_LE(c.overall.maxAbs, 0.012);
    EXPECT_GT(ref.at(32, 40, 0), 0.02f);  // the reference is not empty
}
