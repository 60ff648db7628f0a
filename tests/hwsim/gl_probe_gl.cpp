// weft_gl_probe: timing, rectangles, float targets.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ctime>

#include "tests/hwsim/gl_probe.hpp"

namespace weft::probe {

std::uint64_t mix64(std::uint64_t z) {
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

float unitFloat(std::uint64_t bits) { return static_cast<float>(bits >> 40) * (1.0f / 16777216.0f); }

bool timerQueries() {
    static const bool has = [] {
        GLint bits = 0;
        glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
        glGetError();  // a GL without timer queries may flag the enum
        return bits > 0;
    }();
    return has;
}

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return -1;
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

double cpuNow() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

}  // namespace

void measureInTurn(const Options& o, const std::string& replay, int size, const std::vector<Variant>& variants, Report& report) {
    std::vector<Measurement> out(variants.size());
    std::vector<std::vector<double>> gpu(variants.size());
    GLuint query = 0;
    if (timerQueries()) glGenQueries(1, &query);
    const int rounds = o.warmup + o.repeats;
    for (int run = 0; run < rounds; ++run) {
        for (std::size_t v = 0; v < variants.size(); ++v) {
            variants[v].prepare();
            glFinish();
            const auto t0 = std::chrono::steady_clock::now();
            const double c0 = cpuNow();
            if (query) glBeginQuery(GL_TIME_ELAPSED, query);
            variants[v].passes();
            if (query) glEndQuery(GL_TIME_ELAPSED);
            glFinish();
            const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            const double cpuMs = cpuNow() - c0;
            if (run == rounds - 1 && variants[v].after) variants[v].after();
            if (run < o.warmup) continue;
            out[v].wallMs.push_back(ms);
            out[v].cpuRuns.push_back(cpuMs);
            if (query) {
                GLuint64 ns = 0;
                glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
                gpu[v].push_back(double(ns) * 1e-6);
            }
        }
        std::fprintf(stderr, "[probe] round %d of %d done%s\n", run + 1, rounds, run < o.warmup ? " (warm-up)" : "");
    }
    if (query) glDeleteQueries(1, &query);
    if (glGetError() != GL_NO_ERROR) gl::fail("a GL call failed while timing");
    for (std::size_t v = 0; v < variants.size(); ++v) {
        Measurement& m = out[v];
        m.replay = replay, m.size = size, m.variant = variants[v].label;
        m.medianMs = median(m.wallMs);
        m.gpuMs = query ? median(gpu[v]) : -1;
        m.cpuMs = median(m.cpuRuns);
        m.gpuRuns = gpu[v];
        std::fprintf(stderr, "[probe] %s %d %-12s %9.2f ms\n", replay.c_str(), size, m.variant.c_str(), m.medianMs);
        report.measurements.push_back(std::move(m));
    }
}

GLuint rectProgram(const std::string& fragmentBody) {
    static const std::string vs =
        "#version 330 compatibility\n"
        "uniform vec4 rect;\nuniform vec2 target;\nuniform float depth;\n"
        "void main() {\n"
        "  vec2 c = vec2((gl_VertexID & 1) != 0 ? rect.z : rect.x, (gl_VertexID & 2) != 0 ? rect.w : rect.y);\n"
        "  gl_Position = vec4(c / target * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);\n"
        "}\n";
    return gl::linkProgram(vs, "#version 330 compatibility\nout vec4 color;\n" + fragmentBody);
}

void drawRect(GLuint program, int x0, int y0, int x1, int y1, float depth) {
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    glUseProgram(program);
    glUniform4f(glGetUniformLocation(program, "rect"), float(x0), float(y0), float(x1), float(y1));
    glUniform2f(glGetUniformLocation(program, "target"), float(viewport[2]), float(viewport[3]));
    glUniform1f(glGetUniformLocation(program, "depth"), depth);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

GLuint floatTexture(GLenum internalFormat, int w, int h, const float* data) {
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    const GLenum format = internalFormat == GL_R32F ? GL_RED : internalFormat == GL_RG32F ? GL_RG : GL_RGBA;
    glTexImage2D(GL_TEXTURE_2D, 0, GLint(internalFormat), w, h, 0, format, GL_FLOAT, data);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    return t;
}

GLuint depthStencilBuffer(int w, int h) {
    GLuint rb;
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH32F_STENCIL8, w, h);
    return rb;
}

GLuint framebuffer(GLuint colorTexture, GLuint depthStencil) {
    GLuint fbo;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colorTexture, 0);
    if (depthStencil) glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depthStencil);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) gl::fail("float framebuffer incomplete");
    return fbo;
}

void setInt(GLuint program, const char* name, int v) { glUniform1i(glGetUniformLocation(program, name), v); }
void setFloat(GLuint program, const char* name, float v) { glUniform1f(glGetUniformLocation(program, name), v); }
void setVec2(GLuint program, const char* name, float x, float y) { glUniform2f(glGetUniformLocation(program, name), x, y); }

std::vector<float> readRed(int w, int h) {
    std::vector<float> px(std::size_t(w) * h);
    glReadPixels(0, 0, w, h, GL_RED, GL_FLOAT, px.data());
    return px;
}

}  // namespace weft::probe
