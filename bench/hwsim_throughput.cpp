// hwsim throughput: fragments per second through stipple + depth test (the
// per-fragment loop of the modelled pipeline), measured side by side on one
// and two threads, and against the same passes without stipple and under
// the quad-shading GeForce 7800 profile. Target: >= 100 M fragments/s on two
// cores (stipple + depth, ideal profile). Then the replays' pass lists
// (keller.stipple: stipple + depth; segovia.table1: the Table 1 variants) at
// 1024x1024 under the mesa-llvmpipe profile beside llvmpipe itself timing
// the same passes (weft_gl_probe, medians of 3): fragments per second of
// each and their ratio. Target: hwsim >= llvmpipe.
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "hwsim/pipeline.hpp"
#include "hwsim/replay.hpp"
#include "tests/hwsim/mesa_driver.hpp"

using namespace weft::hwsim;

namespace {

struct Shade {
    void operator()(const Fragment& f, FragmentOutput& o) const { o.color = {f.z, f.z, f.z, 1}; }
};

struct Measure {
    double seconds, cpuSeconds;  // wall clock; CPU time of all threads (shows a loaded machine)
    std::int64_t fragments;
    double rate() const { return double(fragments) / seconds; }
    double cpuRate() const { return double(fragments) / cpuSeconds; }
};

// `passes` full-screen triangles pairs at decreasing depth (every depth test
// passes) or alternating depth (half fail), stippled n x n when n > 0.
Measure run(const char* profileName, int threads, int n, int passes) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const int size = 1024;
    Framebuffer fb(size, size);
    Pipeline pipe(fb, findProfile(profileName));
    pipe.state.depth = {true, CompareFunc::Less, true};
    pipe.state.stipple.enabled = n > 0;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    for (int i = 0; i < passes; ++i) {
        if (n > 0) pipe.state.stipple.rows = StippleState::interleaved(n, i % n, (i / n) % n);
        const float z = (i % 2) ? 0.9f - 0.0001f * i : 0.5f - 0.0001f * i;
        const Vertex a[3] = {{0, 0, z}, {float(size), 0, z}, {float(size), float(size), z}};
        const Vertex b[3] = {{0, 0, z}, {float(size), float(size), z}, {0, float(size), z}};
        pipe.drawTriangle(a, Shade{});
        pipe.drawTriangle(b, Shade{});
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    return {s, cpu, pipe.counts().generated};
}

void report(const char* what, const Measure& m, double base) {
    std::printf("%-60s %8.1f M fragments/s  (x%.2f)  %8.1f M per CPU-second\n", what, m.rate() / 1e6, m.rate() / base,
                m.cpuRate() / 1e6);
}

#ifdef WEFT_GL_PROBE
// Median ms per replay summed over its variants, from weft_gl_probe on llvmpipe.
std::map<std::string, double> llvmpipeMs(int size) {
    const std::string cmd = weft::crosscheck::mesaDriverEnv("llvmpipe") + WEFT_GL_PROBE + " --repeats 3 --sizes " + std::to_string(size) +
                            " 2>/dev/null";
    std::map<std::string, double> ms;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return ms;
    char line[512], replay[64];
    double median = 0;
    while (std::fgets(line, sizeof line, pipe))
        if (std::sscanf(line, "RESULT replay=%63s size=%*d variant=%*s median_ms=%lf", replay, &median) == 2) ms[replay] += median;
    pclose(pipe);
    return ms;
}

void replaysBesideLlvmpipe() {
    const int size = 1024;
    const std::map<std::string, double> gl = llvmpipeMs(size);
    std::printf("\nreplays at %dx%d, mesa-llvmpipe profile (hwsim, 2 threads, median of 3 replays) vs llvmpipe (weft_gl_probe, median of 3 timed passes)\n", size, size);
    for (const char* replay : {"keller.stipple", "segovia.table1"}) {
        // The median of three runs, as the probe times llvmpipe.
        ReplayResult r;
        std::vector<double> seconds;
        for (int run = 0; run < 3; ++run) {
            const auto t0 = std::chrono::steady_clock::now();
            r = runReplay(replay, findProfile("mesa-llvmpipe"), {{"width", std::to_string(size)}, {"height", std::to_string(size)}});
            seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
        std::sort(seconds.begin(), seconds.end());
        const double hwsimS = seconds[1];
        double fragments = 0;
        for (const ReplayVariant& v : r.variants) fragments += double(v.counters.at("fragments.generated"));
        const auto it = gl.find(replay);
        if (it == gl.end()) {
            std::printf("%-16s hwsim %8.1f M fragments/s; llvmpipe: weft_gl_probe gave no times\n", replay, fragments / hwsimS / 1e6);
            continue;
        }
        const double glRate = fragments / (it->second * 1e-3), hwsimRate = fragments / hwsimS;
        std::printf("%-16s hwsim %8.1f M fragments/s  llvmpipe %8.1f M fragments/s  hwsim/llvmpipe x%.2f (target >= 1: %s)\n", replay,
                    hwsimRate / 1e6, glRate / 1e6, hwsimRate / glRate, hwsimRate >= glRate ? "met" : "NOT met");
    }
}
#endif

}  // namespace

int main(int argc, char** argv) {
    const int passes = argc > 1 ? std::stoi(argv[1]) : 64;
    run("ideal", 2, 4, 4);  // warm up
    const Measure two = run("ideal", 2, 4, passes);
    const double base = two.rate();
    std::printf("hwsim throughput, %d passes of 1024x1024 (%lld fragments), depth LESS\n", passes, (long long)two.fragments);
    report("stipple 4x4 + depth, ideal, 2 threads", two, base);
    report("stipple 4x4 + depth, ideal, 1 thread", run("ideal", 1, 4, passes), base);
    report("depth only, ideal, 2 threads", run("ideal", 2, 0, passes), base);
    report("stipple 4x4 + depth, geforce-7800 (late, quads), 2 threads", run("geforce-7800", 2, 4, passes), base);
    report("stipple 4x4 + depth, modern-desktop, 2 threads", run("modern-desktop", 2, 4, passes), base);
    std::printf("target: >= 100 M fragments/s through stipple + depth on 2 cores: %s (%.1f M/s)\n",
                base >= 100e6 ? "met" : "NOT met", base / 1e6);
#ifdef WEFT_GL_PROBE
    replaysBesideLlvmpipe();
#endif
    return 0;
}
