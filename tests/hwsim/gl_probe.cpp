// weft_gl_probe [--sizes 512,1024] [--repeats N] [--warmup N] [--quick]
//               [--replays segovia.table1,keller.stipple] [--lights N] [--light-cost N] [--out probe.json]
// Times hwsim's replays' pass lists on the GL that EGL finds (gl_probe.hpp)
// and prints, after the RENDERER line, one line per (replay, size, variant):
//   RESULT replay=segovia.table1 size=512 variant=stencil_2x2 median_ms=.. gpu_ms=.. cpu_ms=.. min_ms=.. max_ms=.. runs=N
// (median_ms: wall clock, glFinish to glFinish; gpu_ms: median GL_TIME_ELAPSED,
// -1 without timer queries; cpu_ms: the process's CPU time, all threads, the
// work of a software GL on a shared machine), and whether the
// variants that must agree made identical images:
//   IMAGES replay=segovia.table1 size=512 identical=yes what
// --out writes the same as JSON (bench/hwsim_calibrate.py reads it).
// Progress goes to stderr. Bad options: one line, exit 1; GL failures: exit 2.
// Built by CMake (target weft_gl_probe) or alone, e.g. on a GPU machine:
//   g++ -std=c++20 -O2 -I. tests/hwsim/gl_probe*.cpp tests/hwsim/gl_context.cpp -o weft_gl_probe
//       -static-libstdc++ -static-libgcc -lEGL -lOpenGL
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/hwsim/gl_probe.hpp"

namespace {

using namespace weft::probe;

[[noreturn]] void usage(const std::string& why) {
    std::fprintf(stderr, "weft_gl_probe: %s\n", why.c_str());
    std::exit(1);
}

int integer(const std::string& option, const char* text, int min, int max) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (!*text || *end || v < min || v > max)
        usage(option + " must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], not '" + text + "'");
    return int(v);
}

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    for (std::string item; std::getline(in, item, ',');) out.push_back(item);
    return out;
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--quick") { o.repeats = 3; continue; }
        if (i + 1 >= argc) usage("unknown option or missing value: '" + a + "'");
        const char* v = argv[++i];
        if (a == "--repeats") o.repeats = integer(a, v, 1, 1000);
        else if (a == "--warmup") o.warmup = integer(a, v, 0, 100);
        else if (a == "--lights") o.lights = integer(a, v, 1, 256);
        else if (a == "--light-cost") o.lightCost = integer(a, v, 1, 100000);
        else if (a == "--out") o.out = v;
        else if (a == "--sizes") {
            o.sizes.clear();
            for (const std::string& s : split(v)) {
                o.sizes.push_back(integer(a, s.c_str(), 1, 8192));
                if (o.sizes.back() % 4) usage("--sizes: " + s + " is not a multiple of 4 (the 4x4 pattern)");
            }
        } else if (a == "--replays") {
            o.replays = split(v);
            for (const std::string& r : o.replays)
                if (r != "segovia.table1" && r != "keller.stipple") usage("--replays: unknown replay '" + r + "' (segovia.table1, keller.stipple)");
        } else usage("unknown option '" + a + "'");
    }
    if (o.sizes.empty() || o.replays.empty()) usage("--sizes and --replays need at least one entry");
    return o;
}

std::string jsonString(const std::string& s) {
    std::string out = "\"";
    for (char c : s) out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    return out + "\"";
}

std::string toJson(const Options& o, const std::string& renderer, const Report& r) {
    std::ostringstream j;
    j << "{\n  \"renderer\": " << jsonString(renderer) << ",\n  \"timer_queries\": " << (timerQueries() ? "true" : "false")
      << ",\n  \"repeats\": " << o.repeats << ", \"warmup\": " << o.warmup << ",\n  \"params\": {\"segovia.table1\": {\"lights\": "
      << o.lights << ", \"light_cost\": " << o.lightCost << "}},\n  \"results\": [\n";
    for (std::size_t i = 0; i < r.measurements.size(); ++i) {
        const Measurement& m = r.measurements[i];
        j << "    {\"replay\": " << jsonString(m.replay) << ", \"size\": " << m.size << ", \"variant\": " << jsonString(m.variant)
          << ", \"median_ms\": " << m.medianMs << ", \"gpu_ms\": " << m.gpuMs << ", \"cpu_ms\": " << m.cpuMs
          << ", \"wall_ms\": [";
        for (std::size_t k = 0; k < m.wallMs.size(); ++k) j << (k ? ", " : "") << m.wallMs[k];
        j << "], \"cpu_ms_runs\": [";
        for (std::size_t k = 0; k < m.cpuRuns.size(); ++k) j << (k ? ", " : "") << m.cpuRuns[k];
        j << "], \"gpu_ms_runs\": [";
        for (std::size_t k = 0; k < m.gpuRuns.size(); ++k) j << (k ? ", " : "") << m.gpuRuns[k];
        j << "]}" << (i + 1 < r.measurements.size() ? "," : "") << "\n";
    }
    j << "  ],\n  \"images\": [\n";
    for (std::size_t i = 0; i < r.images.size(); ++i) {
        const ImageCheck& c = r.images[i];
        j << "    {\"replay\": " << jsonString(c.replay) << ", \"size\": " << c.size << ", \"what\": " << jsonString(c.what)
          << ", \"identical\": " << (c.identical ? "true" : "false") << "}" << (i + 1 < r.images.size() ? "," : "") << "\n";
    }
    j << "  ]\n}\n";
    return j.str();
}

void writeAtomically(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".tmp";
    std::ofstream out(tmp);
    out << text;
    out.close();
    if (!out) weft::gl::fail("cannot write '" + tmp + "'");
    std::filesystem::rename(tmp, path);
}

std::string underscored(std::string s) {
    std::replace(s.begin(), s.end(), ' ', '_');
    return s;
}

// The lines not printed yet (each replay's as it finishes: a long run shows its figures early).
void print(const Report& r, std::size_t& measurementsDone, std::size_t& imagesDone) {
    for (; measurementsDone < r.measurements.size(); ++measurementsDone) {
        const Measurement& m = r.measurements[measurementsDone];
        const auto [lo, hi] = std::minmax_element(m.wallMs.begin(), m.wallMs.end());
        std::printf("RESULT replay=%s size=%d variant=%s median_ms=%.3f gpu_ms=%.3f cpu_ms=%.3f min_ms=%.3f max_ms=%.3f runs=%zu\n",
                    m.replay.c_str(), m.size, underscored(m.variant).c_str(), m.medianMs, m.gpuMs, m.cpuMs, *lo, *hi, m.wallMs.size());
    }
    for (; imagesDone < r.images.size(); ++imagesDone) {
        const ImageCheck& c = r.images[imagesDone];
        std::printf("IMAGES replay=%s size=%d identical=%s %s\n", c.replay.c_str(), c.size, c.identical ? "yes" : "NO", c.what.c_str());
    }
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    if (!o.out.empty()) {
        const auto dir = std::filesystem::path(o.out).parent_path();
        if (!dir.empty() && !std::filesystem::is_directory(dir)) usage("--out: no directory '" + dir.string() + "'");
    }
    weft::gl::makeContext(3, 3);
    const std::string renderer = weft::gl::rendererString();
    std::printf("RENDERER %s\n", renderer.c_str());
    std::fflush(stdout);
    GLuint vao;  // attributeless rectangles
    glGenVertexArrays(1, &vao);
    Report report;
    std::size_t measurementsDone = 0, imagesDone = 0;
    for (int size : o.sizes)
        for (const std::string& replay : o.replays) {
            glBindVertexArray(vao);
            if (replay == "segovia.table1") runSegovia(o, size, report);
            else runKeller(o, size, report);
            print(report, measurementsDone, imagesDone);
        }
    if (!o.out.empty()) writeAtomically(o.out, toJson(o, renderer, report));
    return 0;
}
