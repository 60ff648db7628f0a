// The volume BVH answers exactly what testing every box answers, in
// ascending order, for random boxes and rays, and at the edge cases.
#include <gtest/gtest.h>

#include <random>

#include "core/volume/media/volume_bvh.hpp"

using namespace weft;

namespace {

std::vector<std::uint32_t> bruteForce(const std::vector<BBoxd>& boxes, const Vec3d& o, const Vec3d& d, double tMax) {
    std::vector<std::uint32_t> out;
    for (std::uint32_t i = 0; i < boxes.size(); ++i)
        if (rayMeetsBox(boxes[i], o, d, tMax)) out.push_back(i);
    return out;
}

std::vector<BBoxd> randomBoxes(int n, std::mt19937& rng) {
    std::uniform_real_distribution<double> pos(-10, 10), size(0.01, 3);
    std::vector<BBoxd> boxes;
    for (int i = 0; i < n; ++i) {
        const Vec3d lo(pos(rng), pos(rng), pos(rng));
        boxes.emplace_back(lo, lo + Vec3d(size(rng), size(rng), size(rng)));
    }
    return boxes;
}

}  // namespace

TEST(VolumeBvh, MeetsTheSameBoxesAsTestingEveryOne) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-12, 12);
    for (int n : {1, 2, 3, 5, 17, 200}) {
        const std::vector<BBoxd> boxes = randomBoxes(n, rng);
        const VolumeBvh bvh(boxes);
        EXPECT_LT(bvh.nodeCount(), 2 * boxes.size());
        std::vector<std::uint32_t> got;
        int met = 0;
        for (int r = 0; r < 500; ++r) {
            const Vec3d o(u(rng), u(rng), u(rng)), d = Vec3d(u(rng), u(rng), u(rng)).unitSafe();
            const double tMax = r % 3 == 0 ? std::numeric_limits<double>::infinity() : std::abs(u(rng));
            bvh.query(o, d, tMax, got);
            ASSERT_EQ(got, bruteForce(boxes, o, d, tMax)) << n << " boxes, ray " << r;
            met += int(got.size());
        }
        EXPECT_GT(met, 0) << n;  // the rays do meet boxes: the equality is not of empty lists only
    }
}

TEST(VolumeBvh, EdgeCases) {
    const VolumeBvh none{std::vector<BBoxd>{}};
    std::vector<std::uint32_t> got{9};
    none.query(Vec3d(0), Vec3d(1, 0, 0), 1e30, got);
    EXPECT_TRUE(got.empty());

    const BBoxd unit(Vec3d(0), Vec3d(1));
    EXPECT_TRUE(rayMeetsBox(unit, Vec3d(0.5, 0.5, -1), Vec3d(0, 0, 1), 1e30));   // axis-parallel, through
    EXPECT_FALSE(rayMeetsBox(unit, Vec3d(1.5, 0.5, -1), Vec3d(0, 0, 1), 1e30));  // parallel, outside the x slab
    EXPECT_FALSE(rayMeetsBox(unit, Vec3d(0.5, 0.5, -1), Vec3d(0, 0, 1), 0.5));  // stops short
    EXPECT_TRUE(rayMeetsBox(unit, Vec3d(0.5, 0.5, 0.5), Vec3d(1, 0, 0), 0));     // starts inside, zero length
    EXPECT_FALSE(rayMeetsBox(unit, Vec3d(0.5, 0.5, 2), Vec3d(0, 0, 1), 1e30));   // behind the origin
    EXPECT_FALSE(rayMeetsBox(unit, Vec3d(0.5, 0.5, -1), Vec3d(0, 0, std::nan("")), 1e30));
    // Huge and tiny boxes.
    const VolumeBvh bvh({BBoxd(Vec3d(-1e30), Vec3d(1e30)), BBoxd(Vec3d(1e-9), Vec3d(2e-9))});
    bvh.query(Vec3d(0), Vec3d(1, 1, 1).unitSafe(), 1e-8, got);
    EXPECT_EQ(got, (std::vector<std::uint32_t>{0, 1}));
}
