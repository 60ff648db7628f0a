// weft_mesa_check: renders the cross-check pass lists (crosscheck_cases.hpp)
// with the GL implementation EGL finds (headless: Mesa's surfaceless platform,
// the Gallium driver chosen by GALLIUM_DRIVER, or a GPU's EGL device; see
// gl_context.hpp) and prints one line per case:
//   CASE name samples=N invocations=N written=N hash=N
// SAMPLES_PASSED comes from an occlusion query around the passes; the
// invocations from an atomic counter each program increments first (helper
// invocations do not count). Cases needing a missing extension print
//   SKIP name reason
// Anything that stops the checks prints "ERROR reason" and exits 2.
//
// A compatibility context (polygon stipple is compatibility-only), GLSL 3.30
// with ARB_shader_atomic_counters and ARB_shader_image_load_store
// (early_fragment_tests): softpipe offers GL 3.3, llvmpipe 4.5.
#include <cstdio>
#include <cstring>
#include <string>

#include "tests/hwsim/case_lines.hpp"
#include "tests/hwsim/crosscheck_cases.hpp"
#include "tests/hwsim/gl_context.hpp"

namespace {

using namespace weft::crosscheck;
using weft::gl::fail;
using weft::gl::hasExtension;

GLuint program(ProgramKind kind, bool early) {
    const std::string vs = "#version 330 compatibility\nlayout(location = 0) in vec3 p;\n"
                           "void main() { gl_Position = vec4(p.xy / 32.0 - 1.0, p.z * 2.0 - 1.0, 1.0); }\n";
    std::string fs = "#version 330 compatibility\n#extension GL_ARB_shader_atomic_counters : require\n"
                     "#extension GL_ARB_shader_image_load_store : require\n";
    if (early) fs += "layout(early_fragment_tests) in;\n";
    fs += "layout(binding = 0, offset = 0) uniform atomic_uint runs;\nout vec4 color;\nvoid main() {\n"
          "  atomicCounterIncrement(runs);\n  color = vec4(1.0);\n";
    if (kind == ProgramKind::DiscardOdd) fs += "  if ((int(gl_FragCoord.x) & 1) == 1) discard;\n";
    if (kind == ProgramKind::WriteDepth) fs += "  gl_FragDepth = gl_FragCoord.x < 32.0 ? 0.25 : 0.75;\n";
    fs += "}\n";
    return weft::gl::linkProgram(vs, fs);
}

GLenum glFunc(CompareFunc f) {
    static const GLenum m[] = {GL_NEVER, GL_LESS, GL_EQUAL, GL_LEQUAL, GL_GREATER, GL_NOTEQUAL, GL_GEQUAL, GL_ALWAYS};
    return m[int(f)];
}
GLenum glOp(StencilOp op) {
    static const GLenum m[] = {GL_KEEP, GL_ZERO, GL_REPLACE, GL_INCR, GL_DECR, GL_INVERT, GL_INCR_WRAP, GL_DECR_WRAP};
    return m[int(op)];
}
void enable(GLenum cap, bool on) { on ? glEnable(cap) : glDisable(cap); }

bool boundsSupported = false;
bool statisticsSupported = false;

// Queries running around a case's passes: SAMPLES_PASSED and, where offered,
// the pipeline statistics (each target may have one query active at a time).
class CaseQueries {
public:
    CaseQueries() {
        glGenQueries(4, ids_);
        for (int i = 0; i < targets(); ++i) glBeginQuery(kTargets[i], ids_[i]);
    }
    ~CaseQueries() { glDeleteQueries(4, ids_); }
    void end(Counts& counts) {
        for (int i = 0; i < targets(); ++i) glEndQuery(kTargets[i]);
        long long* into[4] = {&counts.samplesPassed, &counts.fsInvocations, &counts.clipIn, &counts.clipOut};
        for (int i = 0; i < targets(); ++i) {
            GLuint64 v = 0;
            glGetQueryObjectui64v(ids_[i], GL_QUERY_RESULT, &v);
            *into[i] = (long long)v;
        }
    }

private:
    static constexpr GLenum kTargets[4] = {GL_SAMPLES_PASSED, GL_FRAGMENT_SHADER_INVOCATIONS_ARB, GL_CLIPPING_INPUT_PRIMITIVES_ARB,
                                           GL_CLIPPING_OUTPUT_PRIMITIVES_ARB};
    static int targets() { return statisticsSupported ? 4 : 1; }
    GLuint ids_[4] = {};
};

void applyState(const PipelineState& s) {
    enable(GL_POLYGON_STIPPLE, s.stipple.enabled);
    if (s.stipple.enabled) {
        GLubyte bytes[128] = {};
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x)
                if (s.stipple.rows[y] >> x & 1u) bytes[4 * y + x / 8] |= GLubyte(0x80u >> (x % 8));
        glPolygonStipple(bytes);
    }
    enable(GL_SCISSOR_TEST, s.scissor.enabled);
    glScissor(s.scissor.x, s.scissor.y, s.scissor.width, s.scissor.height);
    if (boundsSupported) enable(GL_DEPTH_BOUNDS_TEST_EXT, s.bounds.enabled);
    if (s.bounds.enabled) {
        auto bounds = reinterpret_cast<PFNGLDEPTHBOUNDSEXTPROC>(eglGetProcAddress("glDepthBoundsEXT"));
        bounds(s.bounds.zmin, s.bounds.zmax);
    }
    enable(GL_STENCIL_TEST, s.stencil.enabled);
    glStencilFunc(glFunc(s.stencil.func), s.stencil.ref, s.stencil.valueMask);
    glStencilOp(glOp(s.stencil.sfail), glOp(s.stencil.dpfail), glOp(s.stencil.dppass));
    glStencilMask(s.stencil.writeMask);
    enable(GL_DEPTH_TEST, s.depth.enabled);
    glDepthFunc(glFunc(s.depth.func));
    glDepthMask(s.depth.writeMask ? GL_TRUE : GL_FALSE);
}

void runCase(const Case& c) {
    glStencilMask(0xff), glDepthMask(GL_TRUE), glDisable(GL_SCISSOR_TEST);
    glClearColor(0, 0, 0, 0), glClearDepth(c.clearDepth), glClearStencil(c.clearStencil);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    const GLuint zero = 0;
    glBufferSubData(GL_ATOMIC_COUNTER_BUFFER, 0, sizeof zero, &zero);
    Counts counts;
    CaseQueries queries;
    for (const Pass& p : c.passes) {
        static GLuint programs[3][2] = {};
        GLuint& prog = programs[int(p.program)][p.earlyFragmentTests];
        if (!prog) prog = program(p.program, p.earlyFragmentTests);
        glUseProgram(prog);
        applyState(p.state);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(p.triangles.size() * sizeof(Vertex)), p.triangles.data(), GL_STREAM_DRAW);
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(p.triangles.size()));
    }
    queries.end(counts);
    GLuint runs = 0;
    glGetBufferSubData(GL_ATOMIC_COUNTER_BUFFER, 0, sizeof runs, &runs);
    static GLubyte pixels[kSize * kSize * 4];
    glReadPixels(0, 0, kSize, kSize, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    counts.invocations = runs;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            if (pixels[(y * kSize + x) * 4]) counts.markWritten(x, y);
    std::printf("%s\n", caseLine(c.name, counts).c_str());
}

void setUpTarget() {
    GLuint fbo, color, depth;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &color);
    glBindRenderbuffer(GL_RENDERBUFFER, color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, kSize, kSize);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH32F_STENCIL8, kSize, kSize);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) fail("framebuffer incomplete");
    glViewport(0, 0, kSize, kSize);
    GLuint vao, vbo, counter;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), nullptr);
    glEnableVertexAttribArray(0);
    glGenBuffers(1, &counter);
    glBindBuffer(GL_ATOMIC_COUNTER_BUFFER, counter);
    glBufferData(GL_ATOMIC_COUNTER_BUFFER, sizeof(GLuint), nullptr, GL_DYNAMIC_COPY);
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, counter);
}

}  // namespace

int main() {
    weft::gl::makeContext(3, 3);
    std::printf("RENDERER %s\n", weft::gl::rendererString().c_str());
    for (const char* ext : {"GL_ARB_shader_atomic_counters", "GL_ARB_shader_image_load_store"})
        if (!hasExtension(ext)) fail(std::string("the GL implementation lacks ") + ext);
    boundsSupported = hasExtension("GL_EXT_depth_bounds_test");
    statisticsSupported = hasExtension("GL_ARB_pipeline_statistics_query");
    if (!statisticsSupported) std::printf("NOSTATS no GL_ARB_pipeline_statistics_query\n");
    setUpTarget();
    for (const Case& c : allCases()) {
        if (c.needsBounds && !boundsSupported) {
            std::printf("SKIP %s no GL_EXT_depth_bounds_test\n", c.name.c_str());
            continue;
        }
        runCase(c);
    }
    if (glGetError() != GL_NO_ERROR) fail("a GL call failed");
    return 0;
}
