// An empty grid (no active voxel: the first frame of most simulation caches)
// renders a transparent image, in a scene file and as a bare .vdb, with every
// volume technique.
#include <gtest/gtest.h>

#include "plugins/host/render_job.hpp"
#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/vdb_fixtures.hpp"

using namespace weft;

namespace {

float maxValue(const Image& image) {
    float m = 0;
    for (float v : image.data()) m = std::max(m, std::abs(v));
    return m;
}

class EmptyVolume : public ::testing::TestWithParam<const char*> {};

}  // namespace

TEST_P(EmptyVolume, RendersTransparent) {
    test::TempDir dir;
    test::writeEmptyVdb(dir / "empty.vdb");
    test::writeText(dir / "s.json", R"({"volumes": [{"file": "empty.vdb"}], "lights": [{"type": "directional"}]})");
    for (const std::string input : {(dir / "empty.vdb").string(), (dir / "s.json").string()}) {
        const RenderOutcome out = test::render(input, "16x16", {}, GetParam());
        EXPECT_EQ(out.image.width(), 16);
        EXPECT_EQ(maxValue(out.image), 0.0f) << input;
    }
}

INSTANTIATE_TEST_SUITE_P(Techniques, EmptyVolume,
                         ::testing::Values("volume.raymarch", "volume.preint", "volume.adaptive3d", "volume.singlescatter"),
                         [](const auto& info) {
                             std::string n = info.param;
                             for (char& c : n) if (c == '.') c = '_';
                             return n;
                         });
