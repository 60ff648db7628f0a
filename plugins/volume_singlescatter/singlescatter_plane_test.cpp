// volume.singlescatter through the image plane: interleaved patterns and
// wide filters are deterministic at any thread count and converge to the
// default image; a bad pattern is an error naming the key.
#include <gtest/gtest.h>

#include "tests/support/image_plane_checks.hpp"

using namespace weft;

namespace {

const std::string kSmoke = std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb";
const std::string kGround = std::string(WEFT_SOURCE_DIR) + "/scenes/combined/smoke_over_ground.json";
const char* kTech = "volume.singlescatter";

}  // namespace

TEST(SingleScatterPlane, InterleavedPatternConvergesToTheDefault) {
    test::expectImagePlaneVariant(kSmoke, kTech, "32x32", 8, {}, "pattern=interleaved:4x4,basis=lp");
}

TEST(SingleScatterPlane, MitchellFilterConvergesToTheDefault) {
    test::expectImagePlaneVariant(kSmoke, kTech, "32x32", 8, {}, "filter=mitchell");
}

TEST(SingleScatterPlane, MeshesAndVolumesThroughAPatternAreDeterministic) {
    test::expectImagePlaneVariant(kGround, kTech, "24x24", 4, {"gain=0"}, "pattern=interleaved:4x4,basis=lp");
}

TEST(SingleScatterPlane, BadPatternIsAnErrorNamingTheKey) { test::expectBadPatternNamed(kSmoke, kTech); }
