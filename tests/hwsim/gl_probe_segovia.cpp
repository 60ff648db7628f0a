// weft_gl_probe: segovia.table1 on a real GL, pass for pass as the replay
// (hwsim/replays/segovia_table1.cpp): `lights` additive full-screen passes
// over a G-buffer, none / stencil / depth / branch / split for 2x2 and 4x4.
// The G-buffer holds each pixel's own coordinates (what split moves around);
// every light pass runs one program, which reads its pixel from the G-buffer,
// skips lights of other classes when `period` > 1 (branch), and evaluates a
// light with a `light_cost`-iteration loop the compiler cannot drop (its
// result is scaled by a uniform zero). Stencil and depth masks are written
// outside the timed region; split times its split and gather passes.
#include <cstring>

#include "tests/hwsim/gl_probe.hpp"

namespace weft::probe {

namespace {

const char* kLight =
    "uniform sampler2D gbuf;\nuniform int period, lightClass, cost;\nuniform vec2 lightPos;\nuniform float zero;\n"
    "void main() {\n"
    "  vec2 p = texelFetch(gbuf, ivec2(gl_FragCoord.xy), 0).xy;\n"
    "  ivec2 q = ivec2(p);\n"
    "  float v = 0.0;\n"
    "  if (q.x % period + period * (q.y % period) == lightClass) {\n"
    "    float acc = p.x * 0.001 + p.y * 0.002;\n"
    "    for (int i = 0; i < cost; ++i) acc = fract(acc * 1.618034 + 0.3183);\n"
    "    vec2 d = mod(p, 256.0) - lightPos;\n"
    "    v = 64.0 / (64.0 + dot(d, d)) + acc * zero;\n"
    "  }\n"
    "  color = vec4(v, 0.0, 0.0, 0.0);\n"
    "}\n";

const char* kMask =  // keeps the pixels of class `cls` (mask preparation)
    "uniform int n, cls;\n"
    "void main() {\n"
    "  ivec2 f = ivec2(gl_FragCoord.xy);\n"
    "  if (f.x % n + n * (f.y % n) != cls) discard;\n"
    "  color = vec4(0.0);\n"
    "}\n";

const char* kSplit =  // split texel -> its G-buffer pixel
    "uniform sampler2D src;\nuniform int n;\nuniform ivec2 sub;\n"
    "void main() {\n"
    "  ivec2 t = ivec2(gl_FragCoord.xy);\n"
    "  color = texelFetch(src, (t % sub) * n + t / sub, 0);\n"
    "}\n";

const char* kGather =  // pixel -> its split texel
    "uniform sampler2D src;\nuniform int n;\nuniform ivec2 sub;\n"
    "void main() {\n"
    "  ivec2 f = ivec2(gl_FragCoord.xy);\n"
    "  color = texelFetch(src, (f % n) * sub + f / n, 0);\n"
    "}\n";

struct Gl {
    int size = 0, lights = 0, cost = 0;
    GLuint light = 0, mask = 0, split = 0, gather = 0;
    GLuint gbuf = 0, accum = 0, accumFbo = 0, splitGbuf = 0, splitGbufFbo = 0, splitAccum = 0, splitAccumFbo = 0;
};

Gl setUp(const Options& o, int size) {
    Gl g;
    g.size = size, g.lights = o.lights, g.cost = o.lightCost;
    g.light = rectProgram(kLight), g.mask = rectProgram(kMask), g.split = rectProgram(kSplit), g.gather = rectProgram(kGather);
    std::vector<float> coords(std::size_t(size) * size * 2);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) coords[(std::size_t(y) * size + x) * 2] = float(x), coords[(std::size_t(y) * size + x) * 2 + 1] = float(y);
    g.gbuf = floatTexture(GL_RG32F, size, size, coords.data());
    g.accum = floatTexture(GL_R32F, size, size);
    g.accumFbo = framebuffer(g.accum, depthStencilBuffer(size, size));
    g.splitGbuf = floatTexture(GL_RG32F, size, size);
    g.splitGbufFbo = framebuffer(g.splitGbuf);
    g.splitAccum = floatTexture(GL_R32F, size, size);
    g.splitAccumFbo = framebuffer(g.splitAccum);
    glViewport(0, 0, size, size);
    return g;
}

int lightClass(int l, int n) { return l % (n * n); }
float classDepth(int c, int n) { return float(c + 1) / float(n * n + 1); }

void useLight(const Gl& g, GLuint gbuf, int period, int l, int n) {
    glUseProgram(g.light);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, gbuf);
    setInt(g.light, "gbuf", 0), setInt(g.light, "period", period), setInt(g.light, "lightClass", period > 1 ? lightClass(l, n) : 0);
    setInt(g.light, "cost", g.cost), setFloat(g.light, "zero", 0.0f);
    setVec2(g.light, "lightPos", unitFloat(mix64(std::uint64_t(2 * l + 1))) * 256, unitFloat(mix64(std::uint64_t(2 * l + 2))) * 256);
}

void resetState() {
    glDisable(GL_STENCIL_TEST), glDisable(GL_DEPTH_TEST), glDisable(GL_BLEND);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE), glDepthMask(GL_TRUE), glStencilMask(0xff);
}

void clearTargets(const Gl& g) {
    resetState();
    glClearColor(0, 0, 0, 0), glClearDepth(1.0), glClearStencil(0);
    for (GLuint fbo : {g.splitGbufFbo, g.splitAccumFbo}) glBindFramebuffer(GL_FRAMEBUFFER, fbo), glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, g.accumFbo);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

// Class ids into the stencil buffer, or class depths into the depth buffer.
void writeMask(const Gl& g, const std::string& method, int n) {
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glUseProgram(g.mask);
    setInt(g.mask, "n", n);
    for (int c = 0; c < n * n; ++c) {
        setInt(g.mask, "cls", c);
        if (method == "stencil") glEnable(GL_STENCIL_TEST), glStencilFunc(GL_ALWAYS, c, 0xff), glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        else glEnable(GL_DEPTH_TEST), glDepthFunc(GL_ALWAYS), glDepthMask(GL_TRUE);
        drawRect(g.mask, 0, 0, g.size, g.size, method == "depth" ? classDepth(c, n) : 0.0f);
    }
    resetState();
}

void prepare(const Gl& g, const std::string& method, int n) {
    clearTargets(g);
    if (method == "stencil" || method == "depth") writeMask(g, method, n);
}

void additive() { glEnable(GL_BLEND), glBlendFunc(GL_ONE, GL_ONE), glBlendEquation(GL_FUNC_ADD); }

void lightPasses(const Gl& g, const std::string& method, int n) {
    glBindFramebuffer(GL_FRAMEBUFFER, g.accumFbo);
    additive();
    if (method == "stencil") glEnable(GL_STENCIL_TEST), glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP), glStencilMask(0);
    if (method == "depth") glEnable(GL_DEPTH_TEST), glDepthFunc(GL_EQUAL), glDepthMask(GL_FALSE);
    for (int l = 0; l < g.lights; ++l) {
        if (method == "stencil") glStencilFunc(GL_EQUAL, lightClass(l, n), 0xff);
        useLight(g, g.gbuf, method == "branch" ? n : 1, l, n);
        drawRect(g.light, 0, 0, g.size, g.size, method == "depth" ? classDepth(lightClass(l, n), n) : 0.0f);
    }
    resetState();
}

void copyPass(GLuint program, GLuint fbo, GLuint src, int n, int size) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glUseProgram(program);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, src);
    setInt(program, "src", 0), setInt(program, "n", n);
    glUniform2i(glGetUniformLocation(program, "sub"), size / n, size / n);
    drawRect(program, 0, 0, size, size);
}

void splitPasses(const Gl& g, int n) {
    const int sub = g.size / n;
    copyPass(g.split, g.splitGbufFbo, g.gbuf, n, g.size);
    glBindFramebuffer(GL_FRAMEBUFFER, g.splitAccumFbo);
    additive();
    for (int l = 0; l < g.lights; ++l) {
        const int c = lightClass(l, n), x0 = (c % n) * sub, y0 = (c / n) * sub;
        useLight(g, g.splitGbuf, 1, l, n);
        drawRect(g.light, x0, y0, x0 + sub, y0 + sub);
    }
    resetState();
    copyPass(g.gather, g.accumFbo, g.splitAccum, n, g.size);
}

void passes(const Gl& g, const std::string& method, int n) {
    if (method == "split") splitPasses(g, n);
    else lightPasses(g, method, n);
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

void runSegovia(const Options& o, int size, Report& report) {
    const Gl g = setUp(o, size);
    std::vector<Variant> variants{{"none", [&] { prepare(g, "none", 1); }, [&] { passes(g, "none", 1); }, nullptr}};
    std::vector<float> images[2][4];  // [2x2, 4x4][method]: each variant's image after its last run
    const char* methods[] = {"stencil", "depth", "branch", "split"};
    const auto pattern = [](int n) { return std::to_string(n) + "x" + std::to_string(n); };
    for (int k = 0; k < 2; ++k) {
        const int n = 2 << k;
        for (int i = 0; i < 4; ++i) {
            const std::string method = methods[i];
            variants.push_back({method + " " + pattern(n), [&g, method, n] { prepare(g, method, n); },
                                [&g, method, n] { passes(g, method, n); }, [&g, &images, k, i, size] {
                                    glBindFramebuffer(GL_FRAMEBUFFER, g.accumFbo);
                                    images[k][i] = readRed(size, size);
                                }});
        }
    }
    measureInTurn(o, "segovia.table1", size, variants, report);
    for (int k = 0; k < 2; ++k) {
        bool same = true;
        for (int i = 1; i < 4; ++i) same = same && sameBits(images[k][0], images[k][i]);
        report.images.push_back({"segovia.table1", pattern(2 << k) + ": stencil, depth, branch and split images", size, same});
    }
}

}  // namespace weft::probe
