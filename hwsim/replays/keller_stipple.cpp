// keller.stipple — Keller and Heidrich 2001, Sec. 4.1 "Efficient Stipple
// Patterns": interleaved sampling with a pattern repeating every n pixels,
// rendered as n x n passes of the scene, pass (i, j) stippled to the pixels
// with x mod n = i and y mod n = j and shifted by that pixel class's sample
// offset. Compared with supersampling by the same n x n offsets, every pass
// unmasked (the accumulation-buffer way). Interleaving only pays when the
// stipple rejects fragments at scan conversion: where it is applied at the
// end of the pipeline, the program runs as often as for supersampling.
//
// Scene: `triangles` random triangles (seeded) with depth, depth test LESS.
// Offsets: the regular n x n sub-pixel grid ((i + 1/2)/n - 1/2, ...).
#include <cmath>

#include "core/base/rng.hpp"
#include "hwsim/pipeline.hpp"
#include "hwsim/replay.hpp"

namespace weft::hwsim {

namespace {

struct SceneTriangle {
    Vertex v[3];
    float shade;
};

std::vector<SceneTriangle> randomScene(int count, int width, int height, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<SceneTriangle> scene(count);
    for (SceneTriangle& t : scene) {
        const float cx = rng.uniform() * width, cy = rng.uniform() * height;
        const float r = (0.1f + 0.3f * rng.uniform()) * float(std::min(width, height));
        for (Vertex& v : t.v)
            v = {cx + r * (2 * rng.uniform() - 1), cy + r * (2 * rng.uniform() - 1), 0.05f + 0.9f * rng.uniform()};
        t.shade = rng.uniform();
    }
    return scene;
}

// The scene's shading: each triangle's flat shade, picked by gl_PrimitiveID
// (ProgramTraits::flat: hwsim may run it once per triangle and tile).
struct SceneProgram {
    const std::vector<SceneTriangle>* scene;
    int cost;
    void operator()(const Fragment& f, FragmentOutput& o) const {
        const float shade = (*scene)[std::size_t(f.primitive)].shade;
        o.color = {shade, shade, shade, 1};
        o.cost = cost;
    }
};

// One pass: the whole scene in one draw call, shifted by (dx, dy).
void drawScene(Pipeline& pipe, const std::vector<SceneTriangle>& scene, float dx, float dy, int cost) {
    std::vector<std::array<Vertex, 3>> shifted(scene.size());
    for (std::size_t i = 0; i < scene.size(); ++i)
        for (int k = 0; k < 3; ++k) shifted[i][k] = {scene[i].v[k].x + dx, scene[i].v[k].y + dy, scene[i].v[k].z};
    pipe.drawTriangles(shifted, SceneProgram{&scene, cost}, {.flat = true});
}

float offset(int i, int n) { return (float(i) + 0.5f) / float(n) - 0.5f; }

ReplayResult runKeller(const Profile& profile, const ParamSet& p) {
    const int w = int(p.getInt("width")), h = int(p.getInt("height")), n = std::stoi(p.getString("n"));
    const int cost = int(p.getInt("program_cost"));
    const auto scene = randomScene(int(p.getInt("triangles")), w, h, std::uint64_t(p.getInt("seed")));
    ReplayResult result;
    result.baseline = "supersampled";

    Framebuffer interleavedFb(w, h, 1.0f, 1);  // GL_R32F, as the probe renders
    Pipeline interleaved(interleavedFb, profile);
    interleaved.state.depth = {true, CompareFunc::Less, true};
    interleaved.state.stipple.enabled = true;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            interleaved.state.stipple.rows = StippleState::interleaved(n, i, j);
            drawScene(interleaved, scene, -offset(i, n), -offset(j, n), cost);
        }
    result.variants.push_back({"interleaved", withStageCounts(interleaved.counts(), {{"passes", n * n}})});

    Framebuffer superFb(w, h, 1.0f, 1);
    Pipeline super(superFb, profile);
    super.state.depth = {true, CompareFunc::Less, true};
    super.state.blend = {true, BlendFactor::One, BlendFactor::One};  // accumulate
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            super.clearDepth();
            drawScene(super, scene, -offset(i, n), -offset(j, n), cost);
        }
    result.variants.push_back({"supersampled", withStageCounts(super.counts(), {{"passes", n * n}})});

    const double ratio = double(interleaved.counts().invocations) / double(std::max<std::int64_t>(1, super.counts().invocations));
    char line[160];
    std::snprintf(line, sizeof line, "program invocations interleaved / supersampled: %.4f (1/n^2 = %.4f)", ratio, 1.0 / (n * n));
    result.notes.push_back(line);
    return result;
}

const ReplayRegistrar registrar{{
    "keller.stipple",
    "Keller & Heidrich 2001 Sec. 4.1: n x n stipple passes vs supersampling with the full mask",
    ParamTable("keller.stipple",
               {intParam("width", 256, 8, 8192, "image width (pixels)"),
                intParam("height", 256, 8, 8192, "image height (pixels)"),
                enumParam("n", "4", {"2", "4", "8", "16", "32"}, "interleaving period (the stipple repeats every 32 pixels)"),
                intParam("triangles", 64, 1, 100000, "random scene triangles"),
                intParam("seed", 1, 0, 1 << 30, "scene seed"),
                intParam("program_cost", 8, 1, 1000000, "cost units of one program run (fragment_program.cost)")}),
    runKeller,
}};

}  // namespace

}  // namespace weft::hwsim
