// The extremes suite: every registered technique on every extreme input of
// tests/extremes/extreme_cases.hpp, rendered in-process through the same
// path as `weft render`. Each render must give finite channels, work within
// what its settings imply, and the closed form where there is one; a
// technique may refuse a scene it does not render or a setting the case
// changed, with one line naming it. Each case prints its row of the table:
//   build/bin/weft_tests --gtest_filter='Extremes*' | grep '^| '
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/base/error.hpp"
#include "core/scene/scene.hpp"
#include "plugins/host/render_job.hpp"
#include "plugins/technique.hpp"
#include "tests/extremes/extreme_cases.hpp"

using namespace weft;
using namespace weft::test::extremes;

namespace {

// The parameters of a case one technique has: numbers clamped into its table's range.
struct Applied {
    std::vector<std::string> sets;  // key=value
    std::map<std::string, double> numbers;
};

const ParamSpec* findSpec(const TechniqueInfo& info, const std::string& key) {
    for (const ParamSpec& spec : info.params.specs())
        if (spec.name == key) return &spec;
    return nullptr;
}

Applied applicableParameters(const TechniqueInfo& info, const CaseSetup& s) {
    Applied a;
    for (const auto& [key, wanted] : s.extremes)
        if (const ParamSpec* spec = findSpec(info, key)) {
            double v = std::clamp(wanted, spec->min, spec->max);
            if (spec->type == ParamType::Int) v = std::round(v);
            a.sets.push_back(key + "=" + formatNumber(v));
            a.numbers[key] = v;
        }
    for (const auto& [key, text] : s.sets)
        if (findSpec(info, key)) a.sets.push_back(key + "=" + text);
    return a;
}

// A parameter's value in this render: the case's, else the table's default.
double effective(const TechniqueInfo& info, const Applied& a, const std::string& key, double fallback) {
    if (auto it = a.numbers.find(key); it != a.numbers.end()) return it->second;
    const ParamSpec* spec = findSpec(info, key);
    return spec ? std::stod(spec->defaultValue) : fallback;
}

// What the scene holds that bounds the work of a render.
struct SceneSize {
    double rayVoxels = 0;  // sum of the volumes' world diagonals in voxel lengths of the finest one
    double voxels = 0;     // voxels in the volumes' index boxes
    int volumes = 0, lights = 0;
};

SceneSize sceneSize(const std::string& input, double aspect) {
    SceneSize size;
    try {
        const Scene scene = loadScene(input, aspect);
        double finest = 1e300;
        for (const Volume& v : scene.volumes) finest = std::min(finest, v.voxelLength());
        for (const Volume& v : scene.volumes) {
            if (v.empty()) continue;
            const BBoxd box = v.worldBox();
            size.rayVoxels += (box.max() - box.min()).length() / finest;
            size.voxels += double(v.indexBox().volume());
            ++size.volumes;
        }
        size.lights = int(scene.lights.size());
    } catch (const Error&) {  // the render itself reports it
    }
    return size;
}

// Counters bounded by the settings: camera samples by pixels x spp, volume
// marches by the samples x the steps a ray can take, the rest (shadow rays,
// bounces, collision tracking capped at 2^16 per ray) generously but finitely.
void expectBoundedWork(const TechniqueInfo& info, const Applied& a, const CaseSetup& s, const SceneSize& size, const CounterMap& counters) {
    const auto [w, h] = parseResolution(s.resolution);
    const double pixels = double(w) * h, samples = pixels * s.spp;
    double step = 1;
    for (const char* key : {"step", "spacing", "volume_step", "shadowstep"})
        if (findSpec(info, key)) step = std::min(step, effective(info, a, key, 1));
    double steps = size.rayVoxels / step + 8.0 * (size.volumes + 1);
    // Pyramid techniques pad the image and the slice count to blocks of 2^lmax and sample every level.
    const double block = std::ldexp(1.0, int(effective(info, a, "lmax", 0))), levels = effective(info, a, "lmax", 0) + 1;
    const double paddedPixels = std::ceil(w / block) * block * std::ceil(h / block) * block;
    steps = (std::ceil(steps / block) + 1) * block;
    const double vpls = effective(info, a, "vpls", 0), depth = std::max(effective(info, a, "max_depth", 1), effective(info, a, "bounces", 1));
    const double perRay = std::max(steps, 65536.0) * steps;
    const double anything = 64 * (samples + 2 * vpls + size.voxels) * (depth + 2) * (size.lights + 2) *
                            (effective(info, a, "direct_samples", 1) + 1) * (effective(info, a, "bias_compensation", 1) + 1) * perRay;
    for (const auto& [name, value] : counters) {
        double bound = anything;
        if (name == "rays.camera" || name == "image.samples" || name == "samples.indirect" || name == "budget.active_pixels" ||
            name == "fragments.gbuffer")
            bound = samples;
        else if (name == "volume.samples" || name == "composite.ops" || name == "oracle.samples" || name == "synthesis.ops" ||
                 name == "slices" || name.rfind("volume.samples.level", 0) == 0)
            bound = 4 * std::max(samples, paddedPixels * s.spp) * steps * levels * std::max(1, size.volumes);
        else if (name == "fragments.shaded")
            bound = pixels * (2 * vpls + 1);
        EXPECT_GE(value, 0) << info.name << ": counter " << name;
        EXPECT_LE(double(value), bound) << info.name << ": counter " << name << " beyond what the settings imply";
    }
    const auto bad = counters.find("image.nonfinite");
    EXPECT_TRUE(bad == counters.end() || bad->second == 0) << info.name << " produced NaN/Inf values";
}

// A refusal is allowed for content the technique does not render, or for a
// setting the case changed that the message names; always one line.
bool refusalNamesTheCase(const std::string& what, const Applied& a, const CaseSetup& s) {
    // checkTechniqueContent's and requireMeshLights' words for content it does not render.
    if (what.find("it would drop") != std::string::npos || what.find("has none") != std::string::npos) return true;
    if (s.spp != 1 && what.find("spp") != std::string::npos) return true;
    for (const std::string& word : s.mayRefuseNaming)
        if (what.find(word) != std::string::npos) return true;
    for (const std::string& kv : a.sets)
        if (what.find(kv.substr(0, kv.find('='))) != std::string::npos) return true;
    return false;
}

// One technique on one case: "pass", "refused: WHY" or "n/a (...)"; failures are gtest failures.
std::string renderOne(const TechniqueInfo& info, const CaseSetup& s, const std::string& input, const SceneSize& size) {
    const Applied a = applicableParameters(info, s);
    if (s.parametersOnly && a.sets.empty()) return "n/a";
    RenderRequest r;
    r.input = input, r.resolution = parseResolution(s.resolution), r.spp = s.spp, r.technique = info.name, r.threads = 1, r.sets = a.sets;
    const auto t0 = std::chrono::steady_clock::now();
    RenderOutcome out;
    try {
        out = renderToImage(r);
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << info.name << ": an error of more than one line: " << what;
        if (!s.mustRefuseWith.empty())
            EXPECT_NE(what.find(s.mustRefuseWith), std::string::npos) << info.name << ": " << what;
        else
            EXPECT_TRUE(refusalNamesTheCase(what, a, s)) << info.name << " refused without naming the content or setting: " << what;
        return "refused: " + what.substr(0, 90);
    } catch (const std::exception& e) {
        ADD_FAILURE() << info.name << ": an exception not in weft's words: " << e.what();
        return "FAIL";
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_TRUE(s.mustRefuseWith.empty()) << info.name << " rendered what it must refuse";
    const auto [w, h] = parseResolution(s.resolution);
    EXPECT_EQ(out.image.width(), w) << info.name;
    EXPECT_EQ(out.image.height(), h) << info.name;
    EXPECT_TRUE(std::all_of(out.image.data().begin(), out.image.data().end(), [](float v) { return std::isfinite(v); }));
    expectBoundedWork(info, a, s, size, out.counters);
    if (s.closedForm && info.renders != Content::None) s.closedForm(info.name, out.image);
    char text[64];
    std::snprintf(text, sizeof text, "pass (%.0f ms)", ms);
    return text;
}

class Extremes : public ::testing::TestWithParam<ExtremeCase> {};

}  // namespace

TEST_P(Extremes, EveryTechniqueStaysFiniteAndBounded) {
    test::TempDir dir;
    CaseSetup s(dir);
    GetParam().build(s);
    std::string input = s.input;
    if (input.empty()) {
        input = (dir / "scene.json").string();
        test::writeText(input, s.scene.dump(1));
    }
    const auto [w, h] = parseResolution(s.resolution);
    const SceneSize size = sceneSize(input, double(w) / h);
    for (const TechniqueInfo* info : techniques().all()) {
        SCOPED_TRACE(std::string(GetParam().name) + " x " + info->name);
        const std::string result = renderOne(*info, s, input, size);
        std::printf("| %s | %s | %s |\n", GetParam().name, info->name.c_str(), result.c_str());
        std::fflush(stdout);
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, Extremes, ::testing::ValuesIn(extremeCases()),
                         [](const ::testing::TestParamInfo<ExtremeCase>& info) {
                             std::string n = info.param.name;
                             for (char& c : n)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return n;
                         });
