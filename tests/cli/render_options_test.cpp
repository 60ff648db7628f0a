// The render option table (core/base/options/render_options.hpp) read three ways: the
// command line, a batch job and a scene file's render block give the same
// request, reject a bad value with the same text, and follow one precedence.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>

#include "core/base/error.hpp"
#include "core/base/options/render_options.hpp"
#include "core/image/io/image_io.hpp"
#include "plugins/host/render_cli.hpp"
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

TEST(RenderOptions, EffectiveRenderMergesSetKeysCommandLineLast) {
    weft::SceneRender scene, given;
    scene.sets = {"step=0.5", "jitter=true"}, scene.spp = 4, scene.technique = "volume.preint";
    given.sets = {"step=0.25"}, given.seed = 9;
    const weft::EffectiveRender q = weft::effectiveRender(given, scene);
    EXPECT_EQ(q.sets, (std::vector<std::string>{"step=0.5", "jitter=true", "step=0.25"}));
    EXPECT_EQ(q.spp, 4);
    EXPECT_EQ(q.seed, 9u);
    EXPECT_EQ(q.technique, "volume.preint");
    EXPECT_EQ(q.resolution, (weft::Resolution{512, 512}));
    EXPECT_EQ(weft::effectiveRender({}, {}).technique, "volume.raymarch");
    EXPECT_EQ(weft::effectiveRender({}, {.sets = {"compat=vdb_render"}}).technique, "volume.singlescatter");
}

// Each field on its own: the command line's value, else the scene's, else the table's default.
TEST(RenderOptions, EffectiveRenderTakesEachFieldFromTheFirstThatGivesIt) {
    const weft::SceneRender none;
    const weft::SceneRender scene{"volume.preint", {}, weft::Resolution{10, 6}, 3, 5};
    const weft::SceneRender given{"volume.mip", {}, weft::Resolution{4, 4}, 2, 7};
    const weft::EffectiveRender fromGiven = weft::effectiveRender(given, scene);
    EXPECT_EQ(fromGiven.technique, "volume.mip");
    EXPECT_EQ(fromGiven.resolution, (weft::Resolution{4, 4}));
    EXPECT_EQ(fromGiven.spp, 2);
    EXPECT_EQ(fromGiven.seed, 7u);
    const weft::EffectiveRender fromScene = weft::effectiveRender(none, scene);
    EXPECT_EQ(fromScene.technique, "volume.preint");
    EXPECT_EQ(fromScene.resolution, (weft::Resolution{10, 6}));
    EXPECT_EQ(fromScene.spp, 3);
    EXPECT_EQ(fromScene.seed, 5u);
    weft::SceneRender onlySpp;
    onlySpp.spp = 8;  // one field given leaves the others to the scene
    const weft::EffectiveRender mixed = weft::effectiveRender(onlySpp, scene);
    EXPECT_EQ(mixed.spp, 8);
    EXPECT_EQ(mixed.resolution, (weft::Resolution{10, 6}));
    EXPECT_EQ(mixed.seed, 5u);
    const weft::EffectiveRender defaults = weft::effectiveRender(none, none);
    EXPECT_EQ(defaults.resolution, (weft::Resolution{512, 512}));
    EXPECT_EQ(defaults.spp, 1);
    EXPECT_EQ(defaults.seed, 0u);
}

// Values are typed once read: a resolution is two sides, a tile two numbers, frames a list.
TEST(RenderOptions, ValuesAreTypedWhenRead) {
    weft::RenderRequest r;
    const auto give = [&](const char* name, const std::string& text) {
        const weft::RenderOption* o = weft::findRenderOption(name, weft::kInBatchJob);
        ASSERT_NE(o, nullptr) << name;
        weft::applyRenderOption(r, *o, text, name);
    };
    give("resolution", "640X480");
    ASSERT_TRUE(r.resolution);
    EXPECT_EQ(*r.resolution, (weft::Resolution{640, 480}));
    EXPECT_EQ(weft::parseResolution(r.resolution->text()), *r.resolution);  // round trip
    EXPECT_EQ(r.resolution->text(), "640x480");
    give("tile", "2/4");
    EXPECT_EQ(r.tile, (weft::TileSpec{2, 4}));
    give("frames", "3-1,7");
    EXPECT_EQ(r.frames, (std::vector<int>{3, 2, 1, 7}));
    EXPECT_THROW(give("tile", "5/4"), weft::Error);
    give("tile", "");  // the whole image, as an empty --tile always meant
    EXPECT_FALSE(r.tile);
    EXPECT_THROW(weft::requireValid(weft::Resolution{0, 4}), weft::Error);
    weft::SceneRender scene;
    weft::readSceneRender(scene, json{{"res", {64, 32}}}, [](const std::string&, const std::string& m) { throw weft::Error(m); });
    EXPECT_EQ(scene.resolution, (weft::Resolution{64, 32}));
}

// A scene says how it renders, never where the files go or on how many threads.
TEST(RenderOptions, ASceneBlockRefusesRequestOnlyKeys) {
    for (const char* key : {"output", "preview", "stats", "threads", "tile", "frames", "max-memory"}) {
        weft::SceneRender scene;
        std::string message;
        try {
            weft::readSceneRender(scene, json{{key, "x"}}, [](const std::string&, const std::string& m) { throw weft::Error(m); });
        } catch (const weft::Error& e) {
            message = e.what();
        }
        EXPECT_EQ(message.rfind(std::string("render.") + key + " belongs to the command line or a batch job, not to a scene", 0), 0u)
            << key << ": " << message;
    }
}

TEST(RenderOptions, MachineOptionsAreNotSceneSettings) {
    TempDir dir;
    const auto r = runWeft("render " + writeScene(dir, "s.json", R"({"threads": 2})") + " -o " + s(dir / "a.exr"));
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("render.threads belongs to the command line or a batch job"), std::string::npos) << r.output;
    const auto output = runWeft("render " + writeScene(dir, "o.json", R"({"output": "elsewhere.exr"})") + " -o " + s(dir / "a.exr"));
    EXPECT_NE(output.status, 0);
    EXPECT_NE(output.output.find("render.output belongs to the command line or a batch job, not to a scene (scene keys: "
                                 "technique, set, resolution, spp, seed)"), std::string::npos) << output.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "a.exr"));
    EXPECT_FALSE(std::filesystem::exists("elsewhere.exr"));
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

// The host spells every option as weft render has always taken it.
TEST(RenderOptions, CommandLineNamesOfEveryOption) {
    const std::map<std::string, std::string> names = {
        {"input", "input"}, {"output", "-o,--output"}, {"preview", "--preview"}, {"stats", "--stats"}, {"frames", "--frames"},
        {"tile", "--tile"}, {"grid", "--grid"}, {"technique", "--technique"}, {"set", "--set"},
        {"resolution", "--res,--resolution"}, {"spp", "--spp"}, {"seed", "--seed"}, {"threads", "--threads"},
        {"max-memory", "--max-memory"}, {"compression", "--compression"}, {"pixel_type", "-d,--pixel-type"},
        {"verbose", "-v,--verbose"}};
    for (const weft::RenderOption& o : weft::renderOptions()) {
        ASSERT_TRUE(names.count(o.spec.name)) << "a new option: add its spelling here: " << o.spec.name;
        EXPECT_EQ(weft::commandLineNames(o), names.at(o.spec.name));
    }
    EXPECT_EQ(names.size(), weft::renderOptions().size());
    EXPECT_EQ(weft::commandLineLabel(*weft::findRenderOption("resolution", weft::kOnCommandLine)), "--res");
    EXPECT_EQ(weft::commandLineLabel(*weft::findRenderOption("pixel_type", weft::kOnCommandLine)), "--pixel-type");
    EXPECT_EQ(weft::commandLineLabel(*weft::findRenderOption("input", weft::kOnCommandLine)), "input");
    EXPECT_EQ(weft::findRenderOption("spp", weft::kInScene)->label(weft::kInScene), "render.spp");
    EXPECT_EQ(weft::findRenderOption("spp", weft::kInBatchJob)->label(weft::kInBatchJob), "spp");
}

TEST(RenderOptions, HelpRenderListsEveryOption) {
    const auto r = runWeft("help options");
    ASSERT_EQ(r.status, 0) << r.output;
    for (const weft::RenderOption& o : weft::renderOptions()) EXPECT_NE(r.output.find("  " + o.spec.name), std::string::npos) << o.spec.name;
    EXPECT_NE(r.output.find("precedence"), std::string::npos);
}

}  // namespace
