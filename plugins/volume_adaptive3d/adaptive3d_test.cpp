// volume.adaptive3d: Table 1, the skipping rule, equality with volume.preint
// under the minimum oracle, determinism, and savings with a coarse oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>

#include "core/base/rng.hpp"
#include "tests/support/test_support.hpp"
#include "oracles/oracle.hpp"
#include "plugins/volume_adaptive3d/pyramid.hpp"
#include "tests/support/render_helpers.hpp"

using namespace weft;

namespace {

// A test oracle: the same distance (in slices) everywhere, read from a global
// so each test can choose it.
float gConstantSlices = 1;
const OracleRegistrar constantOracle{{"test.constant", "test: a constant distance",
                                      [](const OracleContext& ctx) {
                                          OracleField f;
                                          f.constant = float(gConstantSlices * ctx.sliceSpacing);
                                          return f;
                                      }}};

}  // namespace

TEST(Adaptive3d, SliceLevelsMatchTable1) {
    // Table 1 (lmax unbounded): i = 1..8 -> 0 1 0 2 0 1 0 3; slice 0 starts at lmax.
    const int expected[] = {30, 0, 1, 0, 2, 0, 1, 0, 3};
    for (int i = 0; i <= 8; ++i) EXPECT_EQ(sliceLevel(i, 30), expected[i]) << i;
    EXPECT_EQ(sliceLevel(16, 3), 3);  // bounded by lmax
    EXPECT_EQ(sliceLevel(24, 2), 2);
    EXPECT_EQ(sliceLevel(0, 3), 3);
}

TEST(Adaptive3d, SkippingNeverSamplesMoreSparselyThanTheOracleAsked) {
    // From any composite at slice i with stored distance d, the next slice
    // that is due comes at most d slices later (and never later than 2^lmax).
    Rng rng(42);
    for (int trial = 0; trial < 20000; ++trial) {
        const int lmax = 1 + int(rng.next() % 5);
        const int i = int(rng.next() % 1000);
        const float d = 1.0f + rng.uniform() * float((1 << lmax) - 1);
        int j = i + 1;
        while (!isDue(d, sliceLevel(j, lmax), lmax)) ++j;
        EXPECT_LE(j - i, int(d)) << "lmax " << lmax << " i " << i << " d " << d;
        EXPECT_LE(j - i, 1 << lmax);
    }
}

TEST(Adaptive3d, MinimumOracleEqualsPreintBitForBit) {
    const RenderOutcome pre = test::render("builtin:cloud", "40x30", {}, "volume.preint");
    const RenderOutcome ada = test::render("builtin:cloud", "40x30", {"oracle=minimum"}, "volume.adaptive3d");
    EXPECT_EQ(pre.image.data(), ada.image.data());
    EXPECT_GE(ada.counters.at("volume.samples"), pre.counters.at("volume.samples"));  // worst-case overhead
}

TEST(Adaptive3d, PreintAgreesWithFineRaymarch) {
    const RenderOutcome pre = test::render("builtin:cloud", "48x48", {"spacing=0.5"}, "volume.preint");
    const RenderOutcome ray = test::render("builtin:cloud", "48x48", {"step=0.05", "ert=1"}, "volume.raymarch");
    EXPECT_LT(test::rmse(pre.image, ray.image), 4e-3);
}

TEST(Adaptive3d, ImagesAndCountersIdenticalOnOneAndTwoThreads) {
    gConstantSlices = 3;
    const RenderOutcome a = test::render("builtin:cloud", "37x29", {"oracle=test.constant"}, "volume.adaptive3d", 1);
    const RenderOutcome b = test::render("builtin:cloud", "37x29", {"oracle=test.constant"}, "volume.adaptive3d", 2);
    EXPECT_EQ(a.image.data(), b.image.data());
    EXPECT_EQ(a.counters, b.counters);
}

TEST(Adaptive3d, ConstantOracleCompositesAtLeastEveryDSlices) {
    // Segments empty at both ends are not composited, so compare with d = 1:
    // a ray that composites n non-empty segments at d = 1 composites at least
    // n / d of them at d (less at most one partial segment at each end of
    // the sphere), and larger distances composite less often.
    auto compositesPerRay = [](float d) {
        gConstantSlices = d;
        // Slices 2 voxels apart are wider than these pixels, so distances count in slices.
        const RenderOutcome out = test::render("builtin:sphere", "64x64", {"oracle=test.constant", "spacing=2"}, "volume.adaptive3d");
        return double(out.counters.at("composite.ops")) / (64.0 * 64.0);
    };
    const double dense = compositesPerRay(1);
    EXPECT_GT(dense, 5);  // enough segments per ray for the bounds to mean something
    double previous = dense;
    for (float d : {2.0f, 3.0f, 4.0f, 5.0f, 8.0f}) {
        const double perRay = compositesPerRay(d);
        EXPECT_GE(perRay, dense / d - 2) << "d " << d;
        if (std::has_single_bit(unsigned(d))) {  // d = 3 composites on the slices d = 2 does
            EXPECT_LE(perRay, previous) << "d " << d;
            previous = perRay;
        }
    }
    EXPECT_LT(previous, 0.5 * dense);
}

TEST(Adaptive3d, LargerDistancesTradeAccuracyForSamples) {
    // Slices 4 voxels apart are wider than these pixels, so distances count in slices.
    const RenderOutcome pre = test::render("builtin:cloud", "64x64", {"spacing=4"}, "volume.preint");
    double previousError = -1;
    std::int64_t previousSamples = pre.counters.at("volume.samples") * 2;
    for (float d : {1.0f, 2.0f, 4.0f, 8.0f}) {
        gConstantSlices = d;
        const RenderOutcome ada = test::render("builtin:cloud", "64x64", {"oracle=test.constant", "spacing=4"}, "volume.adaptive3d");
        const double error = test::rmse(ada.image, pre.image);
        EXPECT_GT(error, previousError) << "d " << d;
        EXPECT_LT(ada.counters.at("volume.samples"), previousSamples) << "d " << d;
        previousError = error, previousSamples = ada.counters.at("volume.samples");
    }
    EXPECT_LT(previousSamples * 20, pre.counters.at("volume.samples"));  // d = 8: > 20x fewer samples
}

TEST(Adaptive3d, UnknownOracleIsAClearError) {
    try {
        test::render("builtin:sphere", "8x8", {"oracle=nope"}, "volume.adaptive3d");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("unknown oracle 'nope' (known:"), std::string::npos) << e.what();
    }
}

TEST(Adaptive3d, ExtremesStayFiniteAndBounded) {
    test::TempDir dir;
    test::writeText(dir / "dense.json", R"({"volumes": [{"procedural": "cloud", "resolution": 16,
        "transfer_function": {"points": [{"s": 0, "extinction": 0}, {"s": 0.01, "color": [2, 1, 0], "extinction": 1e30}]}}]})");
    test::writeText(dir / "thin.json", R"({"volumes": [{"procedural": "cloud", "resolution": 16,
        "transfer_function": {"points": [{"s": 0, "extinction": 0}, {"s": 1, "extinction": 1e-30}]}}]})");
    gConstantSlices = 5;
    for (const char* scene : {"dense.json", "thin.json"})
        for (const std::vector<std::string>& sets : std::vector<std::vector<std::string>>{
                 {"spacing=0.015625", "lmax=0"}, {"spacing=64", "lmax=6"}, {"lmax=6", "table_precision=8bit"}, {"table_res=8"}})
            for (const char* technique : {"volume.preint", "volume.adaptive3d"}) {
                std::vector<std::string> all = sets;
                if (std::string(technique) == "volume.adaptive3d") all.push_back("oracle=test.constant");
                else std::erase_if(all, [](const std::string& s) { return s.rfind("lmax=", 0) == 0; });  // preint has no lmax
                const RenderOutcome out = test::render((dir / scene).string(), "7x5", all, technique);
                EXPECT_EQ(out.counters.count("image.nonfinite"), 0u) << scene << " " << technique;
                for (int y = 0; y < 5; ++y)
                    for (int x = 0; x < 7; ++x) {
                        EXPECT_LE(out.image.at(x, y, 3), 1.0f);
                        EXPECT_GE(out.image.at(x, y, 3), 0.0f);
                        EXPECT_LE(out.image.at(x, y, 0), 2.0f * out.image.at(x, y, 3) + 1e-5f);
                    }
            }
}
