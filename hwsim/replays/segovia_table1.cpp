// segovia.table1 — Segovia et al. 2006, Sec. 3.1 and Table 1: accumulating
// `lights` point-light contributions over a G-buffer with an n x n
// interleaved pattern (pixel class c = x mod n + n (y mod n) receives the
// lights l with l mod n^2 = c), one additive pass per light:
//   none       every pixel, every light (no interleaving)
//   stencil    class ids in the stencil buffer, pass l tests EQUAL class(l)
//   depth      class depths in the depth buffer, pass l draws at class(l)'s
//              depth with EQUAL (early-z / hierarchical-z culling)
//   branch     every pixel runs the program, which skips foreign lights
//              with a dynamic branch (cost: lanes in lock step x longest path)
//   split      Sec. 3.2-3.4: split the G-buffer into n^2 contiguous
//              sub-buffers, light each sub-buffer with its lights, gather
// The masks of stencil and depth are prepared with the G-buffer and not
// counted (Table 1 times the light accumulation only); split counts its
// split and gather passes. All interleaved variants make the same image.
// Cost units: a light evaluation costs `light_cost`, a skipped light or a
// texel copy costs 1. The split and gather programs fetch their texel
// through the interleave's permutation, away from their own pixel, which
// texture caches pay for per fetch: the variant's texture.scattered_fetches.
#include <cmath>

#include "core/base/rng.hpp"
#include "hwsim/pipeline.hpp"
#include "hwsim/replay.hpp"

namespace weft::hwsim {

namespace {

struct Setup {
    int w, h, n, lights, lightCost;
    int cls(int x, int y) const { return x % n + n * (y % n); }
    int lightClass(int l) const { return l % (n * n); }
};

// A variant's pipeline counts and its program runs whose texel fetch goes
// through the interleave's permutation.
struct Run {
    StageCounts counts;
    std::int64_t scatteredFetches = 0;
};

// A deterministic irradiance-like contribution of light l at pixel (x, y).
float contribution(int x, int y, int l) {
    const float lx = toUnitFloat(mix64(std::uint64_t(2 * l + 1))) * 256, ly = toUnitFloat(mix64(std::uint64_t(2 * l + 2))) * 256;
    const float dx = float(x % 256) - lx, dy = float(y % 256) - ly;
    return 64.0f / (64.0f + dx * dx + dy * dy);
}

struct LightProgram {  // evaluates light l at its pixel
    int l, cost;
    void operator()(const Fragment& f, FragmentOutput& o) const {
        if (!f.helper) o.color = {contribution(f.x, f.y, l), 0, 0, 0};
        o.cost = cost;
    }
};

void additive(Pipeline& pipe) { pipe.state.blend = {true, BlendFactor::One, BlendFactor::One}; }

Image toImage(const Framebuffer& fb) {
    Image img = Image::rgba(fb.width, fb.height);
    for (int y = 0; y < fb.height; ++y)
        for (int x = 0; x < fb.width; ++x) {
            float* px = img.pixel(x, y);
            px[0] = px[1] = px[2] = fb.colorAt(fb.index(x, fb.height - 1 - y))[0], px[3] = 1;
        }
    return img;
}

Run runNone(const Setup& s, const Profile& profile, Framebuffer& fb) {
    Pipeline pipe(fb, profile);
    additive(pipe);
    for (int l = 0; l < s.lights; ++l) pipe.drawRect(0, 0, s.w, s.h, 0, LightProgram{l, s.lightCost});
    return {pipe.counts()};
}

Run runStencil(const Setup& s, const Profile& profile, Framebuffer& fb) {
    for (int y = 0; y < s.h; ++y)
        for (int x = 0; x < s.w; ++x) fb.stencil[fb.index(x, y)] = std::uint8_t(s.cls(x, y));
    Pipeline pipe(fb, profile);
    additive(pipe);
    pipe.state.stencil = {true, CompareFunc::Equal, 0, 0xff, 0, StencilOp::Keep, StencilOp::Keep, StencilOp::Keep};
    for (int l = 0; l < s.lights; ++l) {
        pipe.state.stencil.ref = std::uint8_t(s.lightClass(l));
        pipe.drawRect(0, 0, s.w, s.h, 0, LightProgram{l, s.lightCost});
    }
    return {pipe.counts()};
}

float classDepth(const Setup& s, int c) { return float(c + 1) / float(s.n * s.n + 1); }

Run runDepth(const Setup& s, const Profile& profile, Framebuffer& fb) {
    for (int y = 0; y < s.h; ++y)
        for (int x = 0; x < s.w; ++x) fb.depth[fb.index(x, y)] = classDepth(s, s.cls(x, y));
    Pipeline pipe(fb, profile);
    additive(pipe);
    pipe.state.depth = {true, CompareFunc::Equal, false};
    for (int l = 0; l < s.lights; ++l)
        pipe.drawRect(0, 0, s.w, s.h, classDepth(s, s.lightClass(l)), LightProgram{l, s.lightCost});
    return {pipe.counts()};
}

Run runBranch(const Setup& s, const Profile& profile, Framebuffer& fb) {
    Pipeline pipe(fb, profile);
    additive(pipe);
    for (int l = 0; l < s.lights; ++l)
        pipe.drawRect(0, 0, s.w, s.h, 0, [&s, l](const Fragment& f, FragmentOutput& o) {
            const bool mine = s.cls(f.x, f.y) == s.lightClass(l);
            o.color = {mine && !f.helper ? contribution(f.x, f.y, l) : 0.0f, 0, 0, 0};
            o.cost = mine ? s.lightCost : 1;
        });
    return {pipe.counts()};
}

// Sub-buffer of class c: the rectangle at (i * w/n, j * h/n) of size w/n x h/n.
Run runSplit(const Setup& s, const Profile& profile, Framebuffer& fb) {
    const int sw = s.w / s.n, sh = s.h / s.n;
    auto source = [&](int sx, int sy, int& x, int& y) {  // split texel -> G-buffer pixel
        const int i = sx / sw, j = sy / sh;
        x = (sx % sw) * s.n + i, y = (sy % sh) * s.n + j;
    };
    Framebuffer split(s.w, s.h, 1.0f, 1);  // GL_R32F, as the probe's split accumulation buffer
    Pipeline pipe(split, profile);
    pipe.drawRect(0, 0, s.w, s.h, 0, [](const Fragment&, FragmentOutput& o) { o.color = {0, 0, 0, 0}; });  // split pass (copy)
    const std::int64_t splitFetches = pipe.counts().invocations;
    additive(pipe);
    for (int l = 0; l < s.lights; ++l) {
        const int c = s.lightClass(l), x0 = (c % s.n) * sw, y0 = (c / s.n) * sh;
        pipe.drawRect(x0, y0, x0 + sw, y0 + sh, 0, [&, l](const Fragment& f, FragmentOutput& o) {
            int x, y;
            source(f.x, f.y, x, y);
            if (!f.helper) o.color = {contribution(x, y, l), 0, 0, 0};
            o.cost = s.lightCost;
        });
    }
    StageCounts counts = pipe.counts();
    Pipeline gather(fb, profile);  // gather pass (copy back)
    gather.drawRect(0, 0, s.w, s.h, 0, [&](const Fragment& f, FragmentOutput& o) {
        const int i = f.x % s.n, j = f.y % s.n;
        o.color = split.texel(split.index(i * sw + f.x / s.n, j * sh + f.y / s.n));
    });
    counts.add(gather.counts());
    return {counts, splitFetches + gather.counts().invocations};
}

ReplayResult runSegovia(const Profile& profile, const ParamSet& p) {
    const int w = int(p.getInt("width")), h = int(p.getInt("height"));
    const int lights = int(p.getInt("lights")), cost = int(p.getInt("light_cost"));
    std::vector<int> patterns;
    for (const std::string& n : {std::string("2"), std::string("4")})
        if (p.getString("patterns") == "both" || p.getString("patterns") == n + "x" + n) patterns.push_back(std::stoi(n));
    ReplayResult result;
    result.baseline = "none";
    {
        Framebuffer fb(w, h, 1.0f, 1);  // GL_R32F, as the probe's accumulation buffer
        const Setup s{w, h, 1, lights, cost};
        const CounterMap own{{"passes", lights}, {"texture.scattered_fetches", 0}};
        result.variants.push_back({"none", withStageCounts(runNone(s, profile, fb).counts, own)});
    }
    using Runner = Run (*)(const Setup&, const Profile&, Framebuffer&);
    const std::pair<const char*, Runner> methods[] = {
        {"stencil", runStencil}, {"depth", runDepth}, {"branch", runBranch}, {"split", runSplit}};
    for (int n : patterns) {
        if (w % n || h % n) throw Error("segovia.table1: width and height must be multiples of " + std::to_string(n));
        const Setup s{w, h, n, lights, cost};
        LargeBuffer<float> first;
        bool same = true;
        for (const auto& [name, run] : methods) {
            Framebuffer fb(w, h, 1.0f, 1);
            const Run r = run(s, profile, fb);
            const std::string label = std::string(name) + " " + std::to_string(n) + "x" + std::to_string(n);
            const int passes = lights + (std::string(name) == "split" ? 2 : 0);
            const CounterMap own{{"passes", passes}, {"texture.scattered_fetches", r.scatteredFetches}};
            result.variants.push_back({label, withStageCounts(r.counts, own)});
            if (first.empty()) first = fb.color;
            else same = same && first == fb.color;
            if (std::string(name) == "split") result.image = toImage(fb);
        }
        result.notes.push_back(std::to_string(n) + "x" + std::to_string(n) + ": stencil, depth, branch and split images " +
                               (same ? "identical" : "DIFFER"));
    }
    return result;
}

const ReplayRegistrar registrar{{
    "segovia.table1",
    "Segovia et al. 2006 Table 1: stencil, depth and branching culling of 2x2/4x4 patterns vs split/gather",
    ParamTable("segovia.table1",
               {intParam("width", 1024, 4, 8192, "G-buffer width (the paper: 1024)"),
                intParam("height", 1024, 4, 8192, "G-buffer height (the paper: 1024)"),
                intParam("lights", 16, 1, 256, "point lights accumulated (the paper: 16)"),
                intParam("light_cost", 32, 1, 1000000, "cost units of one light evaluation (a skip or copy costs 1)"),
                enumParam("patterns", "both", {"both", "2x2", "4x4"}, "interleaving patterns to compare")}),
    runSegovia,
}};

}  // namespace

}  // namespace weft::hwsim
