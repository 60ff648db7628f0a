// The render option table (core/base/options/render_options.hpp) read three ways: the
// command line, a batch job and a scene file's render block give the same
// request, reject a bad value with the same text, and follow one precedence.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/base/error.hpp"
#include "core/base/options/render_options.hpp"
#include "core/image/io/image_io.hpp"
#include "tests/support/test_support.hpp"

using namespace weft::test;
using nlohmann::json;

namespace {

const char* kVolume = R"("volumes": [{"procedural": "sphere", "resolution": 16}])";

std::string s(const std::filesystem::path& p) { return p.string(); }

// A scene of one procedural sphere, with `render` as its render block ("" for none).
std::string writeScene(const TempDir& dir, const std::string& name, const std::string& render) {
    writeText(dir / name, "{" + std::string(kVolume) + (render.empty() ? "" : ",\n \"render\": " + render) + "}\n");
    return s(dir / name);
}

// The stats a render recorded, less what names the input or measures time.
json recorded(const std::filesystem::path& stats) {
    json j = json::parse(readBytes(stats));
    j.erase("input"), j.erase("timings_ms");
    return j;
}

weft::Metadata metadataOf(const std::filesystem::path& exr, std::vector<float>& pixels) {
    weft::Metadata md;
    const weft::Image image = weft::readImage(s(exr), &md);
    pixels.assign(image.data().begin(), image.data().end());
    std::erase_if(md, [](const auto& kv) { return kv.first == "weft:input"; });
    return md;
}

TEST(RenderOptions, CommandLineBatchJobAndSceneBlockGiveTheSameRender) {
    TempDir dir;
    const std::string plain = writeScene(dir, "plain.json", "");
    const std::string block = writeScene(dir, "block.json",
        R"({"technique": "volume.raymarch", "resolution": [12, 8], "spp": 3, "seed": 5, "params": {"step": 0.5, "jitter": true}})");
    auto r = runWeft("render " + plain + " --technique volume.raymarch --res 12x8 --spp 3 --seed 5 --set step=0.5 --set jitter=true -o " +
                     s(dir / "cli.exr") + " --stats " + s(dir / "cli.json"));
    ASSERT_EQ(r.status, 0) << r.output;
    writeText(dir / "jobs.json", json{{"jobs", {{{"input", plain}, {"output", s(dir / "batch.exr")}, {"stats", s(dir / "batch.json")},
                                                  {"technique", "volume.raymarch"}, {"res", "12x8"}, {"spp", 3}, {"seed", 5},
                                                  {"set", {{"step", 0.5}, {"jitter", true}}}}}}}.dump());
    r = runWeft("batch " + s(dir / "jobs.json"));
    ASSERT_EQ(r.status, 0) << r.output;
    r = runWeft("render " + block + " -o " + s(dir / "scene.exr") + " --stats " + s(dir / "scene.json"));
    ASSERT_EQ(r.status, 0) << r.output;

    const json cli = recorded(dir / "cli.json");
    EXPECT_EQ(cli["spp"], "3");
    EXPECT_EQ(cli["seed"], "5");
    EXPECT_EQ(cli["params"]["step"], "0.5");
    EXPECT_EQ(cli["resolution"], json::array({12, 8}));
    EXPECT_EQ(recorded(dir / "batch.json"), cli);
    EXPECT_EQ(recorded(dir / "scene.json"), cli);
    std::vector<float> a, b, c;
    const weft::Metadata md = metadataOf(dir / "cli.exr", a);
    EXPECT_EQ(metadataOf(dir / "batch.exr", b), md);
    EXPECT_EQ(metadataOf(dir / "scene.exr", c), md);
    ASSERT_GE(a.size(), 12u * 8u * 4u);
    EXPECT_TRUE(a == b && a == c) << "the three renders differ";
}

// The part after the label is the same from all three; the label says where.
TEST(RenderOptions, AnOutOfRangeValueIsRejectedWithTheSameTextEverywhere) {
    TempDir dir;
    const std::string plain = writeScene(dir, "plain.json", "");
    const std::string block = writeScene(dir, "block.json", R"({"spp": 0})");
    const auto cli = runWeft("render " + plain + " --spp 0 -o " + s(dir / "a.exr"));
    writeText(dir / "jobs.json", json{{"jobs", {{{"input", plain}, {"output", s(dir / "b.exr")}, {"spp", 0}}}}}.dump());
    const auto batch = runWeft("batch " + s(dir / "jobs.json"));
    const auto scene = runWeft("render " + block + " -o " + s(dir / "c.exr"));
    const std::string text = "spp 0 is outside [1, 1048576]";
    for (const auto* r : {&cli, &batch, &scene}) {
        EXPECT_NE(r->status, 0) << r->output;
        EXPECT_NE(r->output.find(text), std::string::npos) << r->output;
        EXPECT_EQ(std::count(r->output.begin(), r->output.end(), '\n'), 1) << r->output;
    }
    EXPECT_NE(cli.output.find("weft: error: --spp 0 is outside"), std::string::npos) << cli.output;
    EXPECT_NE(batch.output.find("job 1: spp 0 is outside"), std::string::npos) << batch.output;
    EXPECT_NE(scene.output.find("block.json:2:20: render.spp 0 is outside"), std::string::npos) << scene.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "a.exr") || std::filesystem::exists(dir / "b.exr") ||
                 std::filesystem::exists(dir / "c.exr"));
}

TEST(RenderOptions, CommandLineWinsOverTheSceneBlockWhichWinsOverDefaults) {
    TempDir dir;
    const std::string block = writeScene(dir, "block.json", R"({"spp": 3, "seed": 5, "resolution": "10x6", "params": {"step": 0.5}})");
    auto r = runWeft("render " + block + " --spp 2 --set step=0.25 -o " + s(dir / "a.exr") + " --stats " + s(dir / "a.json"));
    ASSERT_EQ(r.status, 0) << r.output;
    json j = recorded(dir / "a.json");
    EXPECT_EQ(j["spp"], "2");             // command line
    EXPECT_EQ(j["seed"], "5");            // scene block
    EXPECT_EQ(j["params"]["step"], "0.25");
    EXPECT_EQ(j["resolution"], json::array({10, 6}));
    EXPECT_EQ(j["technique"], "volume.raymarch");  // default
    r = runWeft("render " + writeScene(dir, "plain.json", "") + " --res 4x4 -o " + s(dir / "b.exr") + " --stats " + s(dir / "b.json"));
    ASSERT_EQ(r.status, 0) << r.output;
    j = recorded(dir / "b.json");
    EXPECT_EQ(j["spp"], "1");
    EXPECT_EQ(j["seed"], "0");
}

TEST(RenderOptions, EffectiveRequestMergesSetKeysCommandLineLast) {
    weft::RenderRequest scene, given;
    scene.sets = {"step=0.5", "jitter=true"}, scene.spp = 4, scene.technique = "volume.preint";
    given.sets = {"step=0.25"}, given.seed = 9;
    const weft::RenderRequest q = weft::effectiveRequest(given, scene);
    EXPECT_EQ(q.sets, (std::vector<std::string>{"step=0.5", "jitter=true", "step=0.25"}));
    EXPECT_EQ(*q.spp, 4);
    EXPECT_EQ(*q.seed, 9u);
    EXPECT_EQ(*q.technique, "volume.preint");
    EXPECT_EQ(*q.resolution, "512x512");
    EXPECT_EQ(*weft::effectiveRequest({}, {}).technique, "volume.raymarch");
}

TEST(RenderOptions, MachineOptionsAreNotSceneSettings) {
    TempDir dir;
    const auto r = runWeft("render " + writeScene(dir, "s.json", R"({"threads": 2})") + " -o " + s(dir / "a.exr"));
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("render.threads belongs to the command line or a batch job"), std::string::npos) << r.output;
    const auto unknown = runWeft("render " + writeScene(dir, "u.json", R"({"sp": 2})") + " -o " + s(dir / "a.exr"));
    EXPECT_NE(unknown.output.find("unknown key 'sp' in render; valid keys: technique, set, resolution, spp, seed"),
              std::string::npos) << unknown.output;
}

TEST(RenderOptions, AliasesAndTypesAreCheckedByTheTable) {
    weft::RenderRequest r;
    const weft::RenderOption* res = weft::findRenderOption("res", weft::kInScene);
    ASSERT_NE(res, nullptr);
    EXPECT_EQ(res->spec.name, "resolution");
    EXPECT_EQ(weft::renderOptionTexts(*res, json::array({64, 32})), std::vector<std::string>{"64x32"});
    EXPECT_THROW(weft::applyRenderOption(r, *res, "0x4", "--res"), weft::Error);
    const weft::RenderOption* spp = weft::findRenderOption("spp", weft::kOnCommandLine);
    try {
        weft::applyRenderOption(r, *spp, "2.5", "--spp");
        ADD_FAILURE() << "2.5 samples accepted";
    } catch (const weft::Error& e) {
        EXPECT_STREQ(e.what(), "--spp '2.5' is not an integer");
    }
    weft::applyRenderOption(r, *spp, "7", "--spp");
    EXPECT_EQ(*r.spp, 7);
    EXPECT_EQ(weft::findRenderOption("threads", weft::kInScene), nullptr);
}

TEST(RenderOptions, HelpRenderListsEveryOption) {
    const auto r = runWeft("help options");
    ASSERT_EQ(r.status, 0) << r.output;
    for (const weft::RenderOption& o : weft::renderOptions()) EXPECT_NE(r.output.find("  " + o.spec.name), std::string::npos) << o.spec.name;
    EXPECT_NE(r.output.find("precedence"), std::string::npos);
}

}  // namespace
