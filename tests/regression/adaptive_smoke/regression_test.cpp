// Image regression of volume.adaptive3d (gradient_alpha oracle) and
// volume.preint on the committed small smoke (data/smoke_small.vdb), with the
// OpenImageIO testsuite's thresholds: fail when more than 2% of pixels
// differ by more than 0.004, or any pixel by more than 0.012.
// Regenerate deliberately with tests/regression/adaptive_smoke/run.sh --update.
#include <gtest/gtest.h>

#include "core/image/io/image_io.hpp"
#include "tests/support/render_helpers.hpp"

using namespace weft;

namespace {

void expectMatchesReference(const std::string& technique, const std::vector<std::string>& sets, const std::string& ref) {
    const std::string dir = std::string(WEFT_SOURCE_DIR) + "/tests/regression/adaptive_smoke/ref/";
    const Image expected = readImage(dir + ref);
    const Image img = test::render(std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb", "96x96", sets, technique).image;
    const ImageComparison c = compareImages(img, expected, 0.004);
    EXPECT_LE(double(c.pixelsAbove) / double(c.pixels), 0.02) << technique << ": " << c.pixelsAbove << " pixels above 0.004";
    EXPECT_LE(c.overall.maxAbs, 0.012) << technique;
}

}  // namespace

TEST(Regression, SmallSmokeAdaptive3dGradientAlpha) {
    expectMatchesReference("volume.adaptive3d", {"oracle=gradient_alpha"}, "adaptive3d_gradient_alpha.exr");
}

TEST(Regression, SmallSmokePreint) { expectMatchesReference("volume.preint", {}, "preint.exr"); }
