#pragma once
// weft_gl_probe: times the pass lists of hwsim's replays (segovia.table1,
// keller.stipple) on the GL that EGL finds, with the replays' parameters, so
// hwsim's predicted times can be calibrated against measured ones. No weft
// library: it builds standalone on a GPU machine with gl_context.cpp.
#include <functional>
#include <string>
#include <vector>

#include "tests/hwsim/gl_context.hpp"

namespace weft::probe {

struct Options {
    std::vector<int> sizes{512, 1024};
    std::vector<std::string> replays{"segovia.table1", "keller.stipple"};
    int repeats = 5, warmup = 1;
    int lights = 16, lightCost = 32;  // segovia.table1's defaults
    std::string out;
};

struct Measurement {
    std::string replay, variant;
    int size = 0;
    double medianMs = 0, gpuMs = -1;  // gpuMs: median GL_TIME_ELAPSED, -1 without timer queries
    double cpuMs = 0;                 // median CPU time of the process (all threads): a software GL's work on a shared machine
    std::vector<double> wallMs, cpuRuns, gpuRuns;  // every timed run
};

struct ImageCheck {
    std::string replay, what;
    int size = 0;
    bool identical = false;
};

struct Report {
    std::vector<Measurement> measurements;
    std::vector<ImageCheck> images;
};

// One variant of a replay: prepare() runs untimed (clears, masks), passes()
// is timed from glFinish to glFinish, after() (optional) runs untimed once
// after its last timed run (reading the image back).
struct Variant {
    std::string label;
    std::function<void()> prepare, passes, after;
};

// Times the variants in turn, one run of each per round: `warmup` rounds
// unrecorded, then `repeats` rounds. A drift of the machine (a software GL's
// memory settling, other work) then spreads over every variant instead of
// landing on whichever ran first. Each variant's measurement goes into the
// report (and a line to stderr), in the variants' order.
void measureInTurn(const Options& o, const std::string& replay, int size, const std::vector<Variant>& variants, Report& report);
bool timerQueries();

// A program drawing pixel rectangles (uniforms rect = x0 y0 x1 y1, target, depth).
GLuint rectProgram(const std::string& fragmentBody);
void drawRect(GLuint program, int x0, int y0, int x1, int y1, float depth = 0.0f);

// Float textures and framebuffers (nearest, no mipmaps).
GLuint floatTexture(GLenum internalFormat, int w, int h, const float* data = nullptr);
GLuint framebuffer(GLuint colorTexture, GLuint depthStencil = 0);
GLuint depthStencilBuffer(int w, int h);

void setInt(GLuint program, const char* name, int v);
void setFloat(GLuint program, const char* name, float v);
void setVec2(GLuint program, const char* name, float x, float y);

// Channel 0 of the bound framebuffer's colour, bit patterns compared by callers.
std::vector<float> readRed(int w, int h);

void runSegovia(const Options& o, int size, Report& report);
void runKeller(const Options& o, int size, Report& report);

// SplitMix64, as weft's rng.hpp (the replays' scenes and lights).
std::uint64_t mix64(std::uint64_t z);
float unitFloat(std::uint64_t bits);

}  // namespace weft::probe
