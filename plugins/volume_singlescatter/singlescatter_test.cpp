// volume.singlescatter: exact agreement with vdb_render's integrator,
// convergence of weft's estimators to the same picture, a homogeneous box
// with a closed form, extremes, determinism, and option errors.
#include <gtest/gtest.h>

#include <openvdb/io/File.h>

#include <cmath>
#include <cstdlib>

#include "core/image/io/image_io.hpp"
#include "core/volume/volume.hpp"
#include "plugins/volume_singlescatter/shared_caches.hpp"
#include "tests/support/render_helpers.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/vdb_fixtures.hpp"

using namespace weft;

namespace {

const std::string kSmoke = std::string(WEFT_SOURCE_DIR) + "/data/smoke_small.vdb";
const char* kTech = "volume.singlescatter";

bool haveVdbRender() { return std::system("command -v vdb_render > /dev/null 2>&1") == 0; }

// Runs vdb_render and reads its EXR.
Image vdbRender(const std::string& vdb, const std::string& args, const test::TempDir& dir) {
    const std::string out = (dir / "vdb_render.exr").string();
    const std::string cmd = "vdb_render '" + vdb + "' '" + out + "' -cpus 2 " + args + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return readImage(out);
}

// A box of constant density in [0, n)^3 voxels of size 1.
std::string writeBox(const test::TempDir& dir, int n, float density) {
    initVdb();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(n - 1)), density, true);
    grid->setName("density");
    const std::string path = (dir / "box.vdb").string();
    openvdb::io::File file(path);
    file.write(openvdb::GridPtrVec{grid});
    return path;
}

void expectFiniteAndBounded(const Image& img, const std::string& what) {
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) {
            const float* p = img.pixel(x, y);
            for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(p[c])) << what;
            ASSERT_GE(p[3], 0.0f) << what;
            ASSERT_LE(p[3], 1.0f) << what;
        }
}

}  // namespace

TEST(SingleScatter, RaymarchReproducesVdbRender) {
    if (!haveVdbRender()) GTEST_SKIP() << "vdb_render is not installed (scripts/install-deps.sh installs it)";
    test::TempDir dir;
    for (const char* extra : {"", "gain=0", "shadowstep=0.7", "rotate=-8,12,5", "fov=30", "lookat=2,25,0"}) {
        std::vector<std::string> sets{"compat=vdb_render", "translate=0,20,80", "estimator=raymarch"};
        std::string args = "-translate 0,20,80 -res 64x48";
        if (*extra) {
            sets.push_back(extra);
            const std::string e(extra);
            args += " -" + e.substr(0, e.find('=')) + " " + e.substr(e.find('=') + 1);
        }
        const RenderOutcome weft = test::render(kSmoke, "64x48", sets, kTech);
        EXPECT_LT(test::rmse(weft.image, vdbRender(kSmoke, args, dir)), 1e-5) << extra;
    }
}

TEST(SingleScatter, FineStepsConvergeToVdbRenderOnSmokeAndSphere) {
    if (!haveVdbRender()) GTEST_SKIP() << "vdb_render is not installed (scripts/install-deps.sh installs it)";
    test::TempDir dir;
    const std::string sphere = (dir / "sphere.vdb").string();
    test::writeProceduralVdb(sphere, "sphere", 48);
    // The sphere is thinner (its edge is a step in density: an opaque one
    // would put all light in the first voxel, where any two quadratures differ).
    struct Case { std::string vdb, translate, absorb, scatter; };
    for (const Case& c : {Case{kSmoke, "0,20,80", "0.1,0.1,0.1", "1.5,1.5,1.5"},
                          Case{sphere, "0.3,0.2,2", "0.01,0.02,0.03", "0.06,0.05,0.04"}}) {
        const Image ref = vdbRender(c.vdb, "-translate " + c.translate + " -absorb " + c.absorb + " -scatter " + c.scatter +
                                               " -res 64x64 -step 0.125 -shadowstep 0.25", dir);
        const RenderOutcome weft = test::render(c.vdb, "64x64",
            {"compat=vdb_render", "translate=" + c.translate, "absorb=" + c.absorb, "scatter=" + c.scatter, "step=0.25",
             "shadowstep=0.25", "cache_voxel=1"}, kTech);
        EXPECT_LT(test::rmse(weft.image, ref), 0.01) << c.vdb;
    }
}

TEST(SingleScatter, HomogeneousBoxMatchesTheClosedForm) {
    // Camera and light on the +z axis looking at a 32^3 box of density 1,
    // no absorption (albedo 1): along the central ray the light and the
    // view share the path, so L = c * (1 - exp(-2 sigma n)) / 2.
    test::TempDir dir;
    const std::string box = writeBox(dir, 32, 1.0f);
    const double sigma = 0.05, c = 0.8;
    const double exact = c * (1 - std::exp(-2 * sigma * 32)) / 2;
    for (const char* estimator : {"cached", "ratio", "raymarch"}) {
        const RenderOutcome out = test::render(box, "9x9",
            {"compat=vdb_render", "translate=15.5,15.5,200", "lookat=15.5,15.5,0", "absorb=0,0,0",
             "scatter=0.05,0.05,0.05", "light=0,0,1,0.8,0.8,0.8", "gain=0", "cutoff=0", "step=0.05",
             "shadowstep=0.05", "cache_voxel=1", std::string("estimator=") + estimator}, kTech);
        EXPECT_NEAR(out.image.pixel(4, 4)[0], exact, 0.02 * exact) << estimator;
        EXPECT_NEAR(out.image.pixel(4, 4)[3], 1 - std::exp(-sigma * 32), 0.01) << estimator;
    }
}

TEST(SingleScatter, ExtremesGiveNoNaN) {
    test::TempDir dir;
    initVdb();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(15)), 2.0f, true);
    grid->tree().setValue(openvdb::Coord(8, 8, 8), std::numeric_limits<float>::quiet_NaN());
    grid->tree().setValue(openvdb::Coord(3, 3, 3), std::numeric_limits<float>::infinity());
    grid->setName("density");
    const std::string nanBox = (dir / "nan.vdb").string();
    openvdb::io::File(nanBox).write(openvdb::GridPtrVec{grid});
    const std::string empty = writeBox(dir, 8, 0.0f);
    const std::vector<std::vector<std::string>> cases = {
        {"absorb=0,0,0", "scatter=0,0,0"}, {"absorb=1e6,1e6,1e6", "scatter=1e6,0,1"}, {"cutoff=0"}, {"cutoff=1"},
        {"step=0.001", "shadowstep=64"}, {"gain=1000"}, {"estimator=ratio"}, {"estimator=raymarch"}};
    for (const std::string& vdb : {nanBox, empty})
        for (const auto& sets : cases) {
            const RenderOutcome out = test::render(vdb, "12x10", sets, kTech);
            expectFiniteAndBounded(out.image, vdb + " " + sets.front());
            EXPECT_EQ(out.counters.count("image.nonfinite"), 0u) << vdb << " " << sets.front();
        }
}

TEST(SingleScatter, IdenticalOnOneAndTwoThreads) {
    for (const char* estimator : {"cached", "ratio"}) {
        const std::vector<std::string> sets{std::string("estimator=") + estimator, "step=2"};
        clearScatterCaches();  // each thread count builds its own light cache
        const RenderOutcome a = test::render(kSmoke, "40x32", sets, kTech, 1);
        clearScatterCaches();
        const RenderOutcome b = test::render(kSmoke, "40x32", sets, kTech, 2);
        EXPECT_EQ(a.image.data(), b.image.data()) << estimator;
        EXPECT_EQ(a.counters, b.counters) << estimator;
    }
}

TEST(SingleScatter, IsotropicHenyeyGreensteinIsIsotropicAndForwardScatteringFollowsTheLight) {
    const std::vector<std::string> base{"light=0,0,-1", "step=2"};  // light behind the smoke, facing the camera
    auto with = [&](std::vector<std::string> extra) {
        extra.insert(extra.end(), base.begin(), base.end());
        return test::render(kSmoke, "24x24", extra, kTech).image;
    };
    const Image iso = with({});
    EXPECT_EQ(with({"phase=hg", "g=0"}).data(), iso.data());
    const Image forward = with({"phase=hg", "g=0.6"}), backward = with({"phase=hg", "g=-0.6"});
    double f = 0, b = 0;
    for (int i = 0; i < 24 * 24; ++i) f += forward.data()[4 * i], b += backward.data()[4 * i];
    EXPECT_GT(f, 2 * b);
}

TEST(SingleScatter, CameraOptionsNeedCompatAndFollowVdbRenderRules) {
    auto error = [](std::vector<std::string> sets) {
        try {
            test::render(kSmoke, "8x8", sets, kTech);
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(error({"translate=0,0,10"}).find("compat=vdb_render"), std::string::npos);
    EXPECT_NE(error({"compat=vdb_render", "rotate=0,10,0", "lookat=0,0,0"}).find("not both"), std::string::npos);
    EXPECT_NE(error({"compat=vdb_render", "fov=30", "focal=20"}).find("not both"), std::string::npos);
    EXPECT_NE(error({"absorb=1,2"}).find("absorb"), std::string::npos);
    EXPECT_NE(error({"light=0,0,0"}).find("light"), std::string::npos);
}

TEST(SingleScatter, VdbRenderCommandLineWorksWithoutNamingTheTechnique) {
    test::TempDir dir;
    const std::string out = (dir / "out.exr").string();
    const auto r = test::runWeft("render '" + kSmoke + "' --set compat=vdb_render --set translate=0,20,80 --res 32x32 -o " +
                                 out + " --stats " + (dir / "s.json").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(test::readBytes(dir / "s.json").find("\"technique\": \"volume.singlescatter\""), std::string::npos);
}
