// Overhead of adaptive indirect budgets (Bauszat et al. 2011, Tables 1 and 2)
// on a real G-buffer (a scene file, 1024x768 by default):
//   Table 1: importance map (W_p over k x k) + exact apportionment of a
//            budget of 4 samples per pixel, for k = 2, 4, 6, 8, 10;
//   Table 2: sample generation and storage for 4, 16 and 64 samples per
//            pixel: exclusive scan, sample-to-pixel buffers in batches of
//            the pixel count, one cosine direction per sample (the paper's
//            hemisphere sample), and the store into per-pixel sums.
// Each figure is the median of --repeat runs on the threads TBB is given.
// Usage: weft_budget_overhead SCENE.json [WIDTHxHEIGHT] [--repeat N] [--threads N]
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <thread>

#include "core/base/error.hpp"
#include "core/screen/gbuffer.hpp"
#include "core/screen/sample_budget.hpp"
#include "core/sampling/pixel_sampler.hpp"

using namespace weft;

namespace {

double medianMs(int repeat, const std::function<void()>& fn) {
    std::vector<double> t;
    for (int i = 0; i < repeat; ++i) {
        const auto start = std::chrono::steady_clock::now();
        fn();
        t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

void table1(const GeometryGuides& g, const std::vector<std::uint8_t>& active, int repeat) {
    const double paper[] = {8.3, 26.2, 50.7, 84.9, 128.7};
    std::printf("\nTable 1: importance + counts, %dx%d, budget 4 spp, minimum 1 (ms, median of %d)\n", g.width, g.height, repeat);
    std::printf("%-8s %11s %9s %9s %14s\n", "window", "importance", "counts", "total", "paper (GTX285)");
    for (int k = 2, row = 0; k <= 10; k += 2, ++row) {
        const ImportanceSettings s{k, 0.3f, 0.1f};
        std::vector<float> imp;
        const double ti = medianMs(repeat, [&] { imp = geometryImportance(g, s); });
        const BudgetRequest req{4 * std::int64_t(imp.size()), 1, 0};
        const double tc = medianMs(repeat, [&] { apportionSamples(imp, active, req); });
        std::printf("%-8s %11.2f %9.2f %9.2f %14.1f\n", (std::to_string(k) + "x" + std::to_string(k)).c_str(), ti, tc, ti + tc, paper[row]);
    }
}

void table2(const GeometryGuides& g, const std::vector<std::uint8_t>& active, int repeat) {
    const double paper[] = {2.3, 3.6, 8.5};
    const std::size_t pixels = std::size_t(g.width) * g.height;
    std::printf("\nTable 2: sample generation and storage, batches of %zu samples (ms, median of %d)\n", pixels, repeat);
    std::printf("%-8s %8s %9s %9s %9s %9s %14s\n", "spp", "scan", "buffers", "generate", "store", "total", "paper (GTX285)");
    const std::vector<float> imp = geometryImportance(g, {4, 0.3f, 0.1f});
    int row = 0;
    for (int spp : {4, 16, 64}) {
        const SampleCounts c = apportionSamples(imp, active, {std::int64_t(spp) * std::int64_t(pixels), 1, 0});
        std::vector<std::int64_t> offsets;
        const double ts = medianMs(repeat, [&] { offsets = exclusiveScan(c.counts); });
        const SampleBatches batches(offsets, std::int64_t(pixels));
        std::vector<std::uint32_t> buf;
        std::vector<Vec3f> dirs;
        std::vector<float> sums(3 * pixels);
        double tb = 0, tg = 0, tst = 0;
        auto once = [&] {
            tb = tg = tst = 0;
            for (std::int64_t b = 0; b < batches.count(); ++b) {
                tb += medianMs(1, [&] { batches.fill(b, buf); });
                tg += medianMs(1, [&] {
                    dirs.resize(buf.size());
                    const std::int64_t b0 = batches.begin(b);
                    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, buf.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t k = r.begin(); k != r.end(); ++k) {
                            const std::uint32_t p = buf[k];
                            const PixelSampler s(0, int(p % std::uint32_t(g.width)), int(p / std::uint32_t(g.width)),
                                                 batches.indexInPixel(b0 + std::int64_t(k), p), c.counts[p]);
                            const std::size_t q = std::size_t(p);
                            dirs[k] = sampleCosine(Vec3f(g.normal.c[0][q], g.normal.c[1][q], g.normal.c[2][q] + 1e-3f).unitSafe(), s.get(0), s.get(1));
                        }
                    });
                });
                tst += medianMs(1, [&] {
                    const std::int64_t b0 = batches.begin(b);
                    batches.forEachPixelRun(b, [&](std::uint32_t p, std::int64_t s0, std::int64_t s1) {
                        for (std::int64_t s = s0; s < s1; ++s)
                            for (int k = 0; k < 3; ++k) sums[3 * p + std::size_t(k)] += dirs[std::size_t(s - b0)][k];
                    });
                });
            }
        };
        std::vector<double> b, gen, st;
        for (int i = 0; i < repeat; ++i) once(), b.push_back(tb), gen.push_back(tg), st.push_back(tst);
        for (auto* v : {&b, &gen, &st}) std::sort(v->begin(), v->end());
        const double mb = b[b.size() / 2], mg = gen[gen.size() / 2], mst = st[st.size() / 2];
        std::printf("%-8d %8.2f %9.2f %9.2f %9.2f %9.2f %14.1f\n", spp, ts, mb, mg, mst, ts + mb + mg + mst, paper[row++]);
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::string scenePath, res = "1024x768";
    int repeat = 11, threads = 0;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc) repeat = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
        else if (scenePath.empty()) scenePath = argv[i];
        else res = argv[i];
    }
    if (scenePath.empty()) {
        std::fprintf(stderr, "usage: weft_budget_overhead SCENE.json [WIDTHxHEIGHT] [--repeat N] [--threads N]\n");
        return 1;
    }
    try {
        const int n = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
        tbb::global_control control(tbb::global_control::max_allowed_parallelism, std::size_t(n));
        RenderSettings s;
        if (std::sscanf(res.c_str(), "%dx%d", &s.width, &s.height) != 2) throw Error("bad resolution '" + res + "'");
        const Scene scene = loadScene(scenePath, double(s.width) / s.height);
        Counters counters;
        const GBuffer g = createGBuffer(scene, s, counters);
        const GeometryGuides guides = guidesOf(g);
        std::vector<std::uint8_t> active(g.texels.size());
        for (std::size_t i = 0; i < active.size(); ++i) active[i] = g.texels[i].background() ? 0 : 1;
        std::printf("%s at %dx%d, %d threads\n", scenePath.c_str(), s.width, s.height, n);
        table1(guides, active, repeat);
        table2(guides, active, repeat);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "weft_budget_overhead: %s\n", e.what());
        return 1;
    }
    return 0;
}
