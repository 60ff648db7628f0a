// weft_gl_probe: keller.stipple on a real GL, as the replay
// (hwsim/replays/keller_stipple.cpp) with its defaults (n = 4, 64 seeded
// triangles, seed 1, program_cost 8): n x n passes of the scene, each
// stippled to one pixel class and shifted by its sub-pixel offset, depth LESS
// ("interleaved"), against n x n unmasked passes accumulated additively with
// a depth clear before each ("supersampled"). The program loops
// `program_cost` times, as the replay's cost units.

#include "tests/hwsim/gl_probe.hpp"

namespace weft::probe {

namespace {

constexpr int kN = 4, kTriangles = 64, kSeed = 1, kProgramCost = 8;

const char* kVertex =
    "#version 330 compatibility\n"
    "layout(location = 0) in vec4 v;\nuniform vec2 target, offset;\nflat out float shade;\n"
    "void main() {\n"
    "  shade = v.w;\n"
    "  gl_Position = vec4((v.xy + offset) / target * 2.0 - 1.0, v.z * 2.0 - 1.0, 1.0);\n"
    "}\n";

const char* kFragment =
    "#version 330 compatibility\n"
    "flat in float shade;\nuniform int cost;\nuniform float zero;\nout vec4 color;\n"
    "void main() {\n"
    "  float acc = gl_FragCoord.x * 0.001;\n"
    "  for (int i = 0; i < cost; ++i) acc = fract(acc * 1.618034 + 0.3183);\n"
    "  color = vec4(shade + acc * zero);\n"
    "}\n";

class Rng {  // weft::Rng
public:
    explicit Rng(std::uint64_t seed) : state_(mix64(seed)) {}
    float uniform() { return unitFloat(mix64(state_ += 0x9E3779B97F4A7C15ull)); }

private:
    std::uint64_t state_;
};

// x, y, z, shade per vertex; the replay's randomScene.
std::vector<float> randomScene(int size) {
    Rng rng(kSeed);
    std::vector<float> v;
    for (int t = 0; t < kTriangles; ++t) {
        const float cx = rng.uniform() * size, cy = rng.uniform() * size;
        const float r = (0.1f + 0.3f * rng.uniform()) * float(size);
        float corner[3][3];
        for (auto& c : corner) {
            const float x = cx + r * (2 * rng.uniform() - 1), y = cy + r * (2 * rng.uniform() - 1);
            c[0] = x, c[1] = y, c[2] = 0.05f + 0.9f * rng.uniform();
        }
        const float shade = rng.uniform();
        for (auto& c : corner) v.insert(v.end(), {c[0], c[1], c[2], shade});
    }
    return v;
}

float offset(int i) { return (float(i) + 0.5f) / float(kN) - 0.5f; }

void stipple(int i, int j) {
    GLubyte bytes[128] = {};
    for (int y = j; y < 32; y += kN)
        for (int x = i; x < 32; x += kN) bytes[4 * y + x / 8] |= GLubyte(0x80u >> (x % 8));
    glPolygonStipple(bytes);
}

struct Gl {
    int size = 0;
    GLuint program = 0, vao = 0, vbo = 0, fbo = 0;
};

Gl setUp(int size) {
    Gl g;
    g.size = size;
    g.program = gl::linkProgram(kVertex, kFragment);
    const std::vector<float> scene = randomScene(size);
    glGenVertexArrays(1, &g.vao);
    glBindVertexArray(g.vao);
    glGenBuffers(1, &g.vbo);
    glBindBuffer(GL_ARRAY_BUFFER, g.vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(scene.size() * sizeof(float)), scene.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
    glEnableVertexAttribArray(0);
    g.fbo = framebuffer(floatTexture(GL_R32F, size, size), depthStencilBuffer(size, size));
    glViewport(0, 0, size, size);
    return g;
}

void prepare(const Gl& g) {
    glBindFramebuffer(GL_FRAMEBUFFER, g.fbo);
    glDisable(GL_BLEND), glDisable(GL_POLYGON_STIPPLE), glDepthMask(GL_TRUE);
    glClearColor(0, 0, 0, 0), glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void drawScene(const Gl& g, int i, int j) {
    glUseProgram(g.program);
    setInt(g.program, "cost", kProgramCost), setFloat(g.program, "zero", 0.0f);
    setVec2(g.program, "target", float(g.size), float(g.size));
    setVec2(g.program, "offset", -offset(i), -offset(j));
    glDrawArrays(GL_TRIANGLES, 0, 3 * kTriangles);
}

void interleaved(const Gl& g) {
    glEnable(GL_DEPTH_TEST), glDepthFunc(GL_LESS), glEnable(GL_POLYGON_STIPPLE);
    for (int j = 0; j < kN; ++j)
        for (int i = 0; i < kN; ++i) stipple(i, j), drawScene(g, i, j);
    glDisable(GL_POLYGON_STIPPLE);
}

void supersampled(const Gl& g) {
    glEnable(GL_DEPTH_TEST), glDepthFunc(GL_LESS);
    glEnable(GL_BLEND), glBlendFunc(GL_ONE, GL_ONE);
    for (int j = 0; j < kN; ++j)
        for (int i = 0; i < kN; ++i) glClear(GL_DEPTH_BUFFER_BIT), drawScene(g, i, j);
    glDisable(GL_BLEND);
}

}  // namespace

void runKeller(const Options& o, int size, Report& report) {
    const Gl g = setUp(size);
    const std::vector<Variant> variants{{"interleaved", [&] { prepare(g); }, [&] { interleaved(g); }, nullptr},
                                        {"supersampled", [&] { prepare(g); }, [&] { supersampled(g); }, nullptr}};
    measureInTurn(o, "keller.stipple", size, variants, report);
    glBindVertexArray(0);
}

}  // namespace weft::probe
