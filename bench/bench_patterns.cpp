// Sample-pattern benchmarks, each measured side by side in one run:
//  1. Poisson-disk dart throwing: 65536 points with the grid-accelerated test
//     (target: under 100 ms), and the plain test at a size it can manage.
//  2. Interleaved regular sub-grids against one regular grid: the image-plane
//     sampler alone, the analytic zone plate and volume.raymarch on the
//     built-in cloud, each with pattern=regular and pattern=interleaved:4x4,
//     alternating runs, median times; throughput ratio interleaved / regular
//     (target >= 0.95).
//  3. Their aliasing: the coherent-aliasing ratio of the error image on the
//     grating and the zone plate, and how much of the regular grid's peak
//     is left at the same frequency in the interleaved error.
// Usage: weft_bench_patterns [--threads N] (default 2)
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/image/compare/image_spectrum.hpp"
#include "core/sampling/generators.hpp"
#include "core/sampling/image_plane.hpp"
#include "plugins/host/render_job.hpp"

using namespace weft;

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

void poisson() {
    std::printf("== Poisson-disk dart throwing (radius 0.65 of hexagonal packing, one thread)\n");
    for (bool grid : {true, false}) {
        const int n = grid ? 65536 : 4096;
        std::vector<double> ms;
        PoissonResult r;
        for (int rep = 0; rep < (grid ? 7 : 3); ++rep) {
            const auto t0 = Clock::now();
            r = poissonDartThrowing(n, 0.65, 1 + rep, grid);
            ms.push_back(msSince(t0));
        }
        std::printf("  %-14s %6d points  %9.2f ms (median)  %.1f darts/point  min distance %.4f\n",
                    grid ? "grid-accel." : "plain", n, median(ms), double(r.darts) / n, r.radius);
    }
    const double fast4k = [] {
        std::vector<double> ms;
        for (int rep = 0; rep < 7; ++rep) {
            const auto t0 = Clock::now();
            poissonDartThrowing(4096, 0.65, 1 + rep, true);
            ms.push_back(msSince(t0));
        }
        return median(ms);
    }();
    std::printf("  grid-accel.      4096 points  %9.2f ms (median)\n", fast4k);
}

RenderRequest request(const std::string& input, const std::string& res, int spp, std::vector<std::string> sets, int threads) {
    RenderRequest r;
    r.input = input, r.resolution = parseResolution(res), r.spp = spp, r.threads = threads, r.sets = std::move(sets);
    return r;
}

// Wall-clock and process CPU time (all threads) of one render. CPU time is
// the fairer cost per sample on a loaded machine; both are printed.
struct Timing {
    double wallMs, cpuMs;
    std::int64_t samples;
};

Timing timeRender(const RenderRequest& r) {
    const auto t0 = Clock::now();
    const std::clock_t c0 = std::clock();
    const RenderOutcome out = renderToImage(r);
    return {msSince(t0), 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC, out.counters.at("image.samples")};
}

template <class TimeOne>
void throughput(const std::string& label, TimeOne timeOne) {
    std::vector<double> rw, iw, rc, ic, jc;
    std::int64_t samples = 0;
    timeOne("regular");  // warm up (scene load, caches)
    for (int rep = 0; rep < 9; ++rep) {
        const Timing a = timeOne("regular"), b = timeOne("interleaved:4x4,basis=jittered"), c = timeOne("jittered");
        rw.push_back(a.wallMs), iw.push_back(b.wallMs), rc.push_back(a.cpuMs), ic.push_back(b.cpuMs), samples = a.samples;
        jc.push_back(c.cpuMs);
    }
    std::printf("  %s, %lld samples per render\n", label.c_str(), (long long)samples);
    std::printf("    wall: regular %8.1f ms (%6.2f Msamples/s)  interleaved:4x4 %8.1f ms (%6.2f Msamples/s)  throughput ratio %.3f\n",
                median(rw), samples / median(rw) / 1e3, median(iw), samples / median(iw) / 1e3, median(rw) / median(iw));
    std::printf("    cpu:  regular %8.1f ms                      interleaved:4x4 %8.1f ms                      throughput ratio %.3f\n",
                median(rc), median(ic), median(rc) / median(ic));
    // The same jittered positions in every pixel (no interleaving): separates
    // the cost of where samples fall (shading) from the cost of interleaving.
    std::printf("    cpu:  jittered (one pattern, irregular positions) %8.1f ms, throughput ratio to regular %.3f\n",
                median(jc), median(rc) / median(jc));
}

void renderThroughput(const std::string& label, const std::string& input, const std::string& res, int spp,
                      std::vector<std::string> common, int threads) {
    throughput(label, [&](const std::string& pattern) {
        std::vector<std::string> sets = common;
        sets.push_back("pattern=" + pattern);
        return timeRender(request(input, res, spp, sets, threads));
    });
}

// The sampling machinery alone: positions from the pattern set, a shader
// that costs the same at every position (no data-dependent branches), and
// the box reconstruction.
void samplerThroughput(int threads) {
    throughput("image-plane sampler alone, 1024^2 at 16 spp", [&](const std::string& pattern) {
        RenderContext ctx;
        ctx.settings.width = ctx.settings.height = 1024, ctx.settings.spp = 16;
        ImagePlaneOptions o;
        o.pattern = pattern;
        struct Flat {
            Rgba operator()(const CameraSample& c) const {
                const float v = float(c.x * 1e-3 + c.y * 2e-3) + c.time;
                return {v, v, v, 1};
            }
            void flush(Counters&) const {}
        };
        const auto t0 = Clock::now();
        const std::clock_t c0 = std::clock();
        ImagePlane(o, ctx.settings).render(ctx, "bench", [] { return Flat{}; });
        return Timing{msSince(t0), 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC, std::int64_t(1024) * 1024 * 16};
    });
    (void)threads;
}

std::vector<double> errorOf(const std::string& scene, const std::string& res, int spp, const std::string& pattern, int threads,
                            int& W, int& H) {
    const Image img = renderToImage(request("builtin:" + scene, res, spp, {"pattern=" + pattern}, threads)).image;
    const Image ref = renderToImage(request("builtin:" + scene, res, 1, {"reference=true"}, threads)).image;
    W = img.width(), H = img.height();
    std::vector<double> e;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) e.push_back(double(img.at(x, y, 0)) - ref.at(x, y, 0));
    return e;
}

void aliasing(const std::string& scene, int spp, int threads) {
    int W = 0, H = 0;
    const auto reg = errorOf(scene, "256x256", spp, "regular", threads, W, H);
    const auto inter = errorOf(scene, "256x256", spp, "interleaved:4x4,basis=jittered", threads, W, H);
    const AliasingPeak pr = coherentAliasing(reg, W, H), pi = coherentAliasing(inter, W, H);
    const auto sr = powerSpectrum(reg, W, H), si = powerSpectrum(inter, W, H);
    const std::size_t at = std::size_t((pr.fy + H) % H) * W + (pr.fx + W) % W;
    std::printf("  %-9s %2d spp: peak ratio regular %9.1f at (%d,%d), interleaved %9.1f at (%d,%d); "
                "interleaved power at the regular peak: %.4f of regular's (noise level ~ %.0f)\n",
                scene.c_str(), spp, pr.ratio, pr.fx, pr.fy, pi.ratio, pi.fx, pi.fy, si[at] / sr[at], std::log(double(W) * H));
}

}  // namespace

int main(int argc, char** argv) {
    int threads = 2;
    for (int i = 1; i + 1 < argc; ++i)
        if (std::strcmp(argv[i], "--threads") == 0) threads = std::max(1, std::atoi(argv[i + 1]));
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
    poisson();
    std::printf("\n== Interleaved regular sub-grids vs one regular grid: cost per sample (%d threads, alternating runs, medians of 9)\n", threads);
    samplerThroughput(threads);
    renderThroughput("analytic zone plate 512^2 at 16 spp", "builtin:zoneplate", "512x512", 16, {}, threads);
    renderThroughput("volume.raymarch cloud 128^2 at 16 spp", "builtin:cloud", "128x128", 16, {"step=1"}, threads);
    std::printf("\n== Their aliasing (error image vs exact reference, 256x256)\n");
    for (int spp : {4, 16}) {
        aliasing("grating", spp, threads);
        aliasing("zoneplate", spp, threads);
    }
    return 0;
}
