// mesh.pathtrace: the furnace (a closed emitting, reflecting enclosure has
// radiance Le / (1 - albedo) everywhere inside), BRDF sampling consistent
// with its density, convergence at the Monte Carlo rate on the Cornell box,
// and thread-count independence.
#include <gtest/gtest.h>

#include "core/lighting/brdf.hpp"
#include "core/image/compare/image_compare.hpp"
#include "core/base/rng.hpp"
#include "tests/support/mesh_fixtures.hpp"
#include "tests/support/render_helpers.hpp"

using namespace weft;

namespace {

Scene furnace(float albedo, float emission) {
    Material m;
    m.diffuse = Vec3f(albedo, albedo, albedo);
    m.emission = Vec3f(emission, emission, emission);
    Scene scene;
    scene.source = "furnace";
    scene.addMesh(test::insideSphere(2.0f, m));
    scene.camera.eye = Vec3d(0.3, -0.2, 0.1);
    scene.camera.target = Vec3d(0.3, -0.2, -1);
    scene.camera.fovY = 90;
    return scene;
}

const std::string kCornell = std::string(WEFT_SOURCE_DIR) + "/scenes/cornell.json";

}  // namespace

TEST(PathTrace, FurnaceWithoutReflectionSeesTheEmissionExactly) {
    const Image img = test::renderScene(furnace(0.0f, 0.7f), "mesh.pathtrace", {}, 8, 8, 4);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) ASSERT_FLOAT_EQ(img.at(x, y, 0), 0.7f);
}

TEST(PathTrace, FurnaceConvergesToEmissionOverOneMinusAlbedo) {
    for (float albedo : {0.5f, 0.8f}) {
        const Image img = test::renderScene(furnace(albedo, 0.5f), "mesh.pathtrace", {{"max_depth", "200"}}, 16, 16, 64, 3);
        const double expected = 0.5 / (1.0 - albedo);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(test::channelMean(img, c), expected, 0.015 * expected) << "albedo " << albedo;
    }
}

TEST(PathTrace, TruncatedPathsGiveTheGeometricSeries) {
    // max_depth = 2 counts emission, one and two reflections: Le (1 + a + a^2).
    const Image img = test::renderScene(furnace(0.5f, 1.0f), "mesh.pathtrace", {{"max_depth", "2"}}, 16, 16, 32, 5);
    EXPECT_NEAR(test::channelMean(img, 1), 1.75, 0.02);
}

TEST(PathTrace, BrdfSamplingMatchesItsDensity) {
    // Directional albedo two ways: importance sampled (f cos / pdf) and with
    // uniform hemisphere directions (2 pi f cos). They must agree, for both
    // glossy lobes and a grazing and a steep view.
    Material m;
    m.diffuse = Vec3f(0.3f, 0.3f, 0.3f), m.glossy = Vec3f(0.5f, 0.5f, 0.5f), m.exponent = 20;
    for (GlossyModel model : {GlossyModel::Phong, GlossyModel::Blinn})
        for (const Vec3f& view : {Vec3f(0.5f, 0.1f, 0.8f), Vec3f(0.9f, 0.0f, 0.25f)}) {
            const Brdf b = Brdf::of(m, model);
            const Vec3f n(0, 0, 1), wo = view.unit();
            Rng rng(11);
            double importance = 0, uniform = 0;
            const int N = 300000;
            for (int i = 0; i < N; ++i) {
                const Vec3f wi = b.sample(wo, n, rng.uniform(), rng.uniform(), rng.uniform());
                if (wi.z() > 0) importance += b.eval(wo, wi, n).x() * wi.z() / b.pdf(wo, wi, n);
                Vec3f u = sampleSphere(rng.uniform(), rng.uniform());
                if (u.z() < 0) u = -u;
                uniform += 2 * M_PI * b.eval(wo, u, n).x() * u.z();
            }
            const char* name = model == GlossyModel::Blinn ? "blinn" : "phong";
            EXPECT_NEAR(importance / N, uniform / N, 0.01) << name << " wo.z " << wo.z();
            EXPECT_LT(importance / N, 0.8 + 0.01) << name << " wo.z " << wo.z();  // no energy created
        }
}

TEST(PathTrace, CornellErrorFallsAtTheMonteCarloRate) {
    RenderRequest r;
    r.input = kCornell, r.resolution = Resolution{16, 16}, r.technique = "mesh.pathtrace", r.sets = {"max_depth=3", "jitter=false"};
    r.spp = 2048, r.seed = 99;
    const Image reference = renderToImage(r).image;
    double err[2];
    int k = 0;
    for (int spp : {16, 64}) {
        r.spp = spp, r.seed = 1;
        err[k++] = test::rmse(renderToImage(r).image, reference);
    }
    // Error^2 = sigma^2 (1/n + 1/2048): from 16 to 64 spp it falls by ~1.96.
    EXPECT_GT(err[0] / err[1], 1.6) << err[0] << " " << err[1];
    EXPECT_LT(err[0] / err[1], 2.4) << err[0] << " " << err[1];
}

TEST(PathTrace, SameImageAtOneAndTwoThreads) {
    const RenderOutcome a = test::render(kCornell, "24x16", {"max_depth=4"}, "mesh.pathtrace", 1);
    const RenderOutcome b = test::render(kCornell, "24x16", {"max_depth=4"}, "mesh.pathtrace", 2);
    EXPECT_EQ(a.image.data(), b.image.data());
    EXPECT_GT(test::channelMean(a.image, 0), 0.01);
}
