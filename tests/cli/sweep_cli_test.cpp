// weft sweep: one process renders every combination, measures it against a
// reference and writes the tables; bad --vary options fail in one line
// before anything renders; the results do not depend on the thread count;
// automatic references are cached by content and settings.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/image/io/image_io.hpp"
#include "tests/support/test_support.hpp"

using namespace weft;
using namespace weft::test;

namespace {

const std::string kScene = "builtin:sphere --res 24x16";

nlohmann::json readJson(const std::filesystem::path& p) {
    std::ifstream in(p);
    return nlohmann::json::parse(in);
}

// The CSV without what depends on the clock: median_ms, min_ms, max_ms and
// front_time (the front of time against error).
std::string csvWithoutTimes(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::string out, line;
    std::vector<std::size_t> drop;
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::stringstream s(line);
        for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
        if (drop.empty())
            for (std::size_t i = 0; i < cells.size(); ++i)
                if ((cells[i].size() > 3 && cells[i].compare(cells[i].size() - 3, 3, "_ms") == 0) || cells[i] == "front_time")
                    drop.push_back(i);
        for (std::size_t i = 0; i < cells.size(); ++i)
            if (std::find(drop.begin(), drop.end(), i) == drop.end()) out += cells[i] + ",";
        out += "\n";
    }
    return out;
}

}  // namespace

TEST(SweepCli, MeasuresEveryCombinationAgainstTheReference) {
    TempDir dir;
    ASSERT_EQ(runWeft("render " + kScene + " --set step=0.05 --spp 4 -o " + (dir / "ref.exr").string()).status, 0);
    const auto out = runWeft("sweep " + kScene + " --spp 4 --technique volume.raymarch --vary step=0.05,0.5,2 --vary jitter=false,true "
                             "--reference " + (dir / "ref.exr").string() + " --no-plot -o " + (dir / "s").string());
    ASSERT_EQ(out.status, 0) << out.output;
    const auto j = readJson(dir / "s" / "sweep.json");
    ASSERT_EQ(j["runs"].size(), 6u);
    EXPECT_EQ(j["runs"][0]["label"], "step=0.05 jitter=false");
    EXPECT_EQ(j["runs"][5]["label"], "step=2 jitter=true");
    // The run that repeats the reference's settings reproduces it exactly;
    // coarser steps cost fewer samples and err more.
    EXPECT_EQ(j["runs"][0]["error"]["rmse"].get<double>(), 0.0);
    EXPECT_EQ(j["runs"][0]["error"]["flip"].get<double>(), 0.0);
    EXPECT_GT(j["runs"][4]["error"]["rmse"].get<double>(), j["runs"][2]["error"]["rmse"].get<double>());
    EXPECT_GT(j["runs"][0]["samples"].get<long long>(), j["runs"][2]["samples"].get<long long>());
    EXPECT_GT(j["runs"][2]["samples"].get<long long>(), j["runs"][4]["samples"].get<long long>());
    EXPECT_TRUE(j["runs"][0]["front"]["samples"].get<bool>());  // the only error-free run
    for (const char* f : {"sweep.csv", "sweep.md"}) EXPECT_TRUE(std::filesystem::exists(dir / "s" / f)) << f;
    EXPECT_FALSE(std::filesystem::exists(dir / "s" / "sweep.png"));  // --no-plot
}

TEST(SweepCli, ResultsDoNotDependOnTheThreadCount) {
    TempDir dir;
    ASSERT_EQ(runWeft("render " + kScene + " --set step=0.1 -o " + (dir / "ref.exr").string()).status, 0);
    for (const char* threads : {"1", "2"}) {
        const auto out = runWeft("sweep " + kScene + " --threads " + threads + " --technique volume.raymarch --vary step=0.5,1 "
                                 "--vary jitter=true --technique volume.preint --vary spacing=1,2 --reference " +
                                 (dir / "ref.exr").string() + " --no-plot -o " + (dir / threads).string());
        ASSERT_EQ(out.status, 0) << out.output;
    }
    const std::string one = csvWithoutTimes(dir / "1" / "sweep.csv");
    EXPECT_EQ(one, csvWithoutTimes(dir / "2" / "sweep.csv"));
    EXPECT_NE(one.find("volume.preint"), std::string::npos);
}

TEST(SweepCli, BadVaryIsOneLineBeforeAnythingRenders) {
    TempDir dir;
    ASSERT_EQ(runWeft("render " + kScene + " -o " + (dir / "ref.exr").string()).status, 0);
    const std::string tail = " --reference " + (dir / "ref.exr").string() + " -o " + (dir / "s").string();
    const struct {
        std::string vary, expected;
    } cases[] = {
        {"--vary nope=1,2", "nope"},
        {"--vary step=0.5,0", "step=0"},
        {"--vary step=", "--vary 'step='"},
        {"--vary step=1,,2", "an empty value"},
        {"--vary spp=0,1", "spp"},
        {"--vary step=1 --vary step=2", "given twice"},
        {"--technique no.such --vary spp=1", "no.such"},
        {"--vary res=32x32", "32x32"},  // the reference is 24x16
    };
    for (const auto& c : cases) {
        const auto out = runWeft("sweep " + kScene + " " + c.vary + tail);
        EXPECT_NE(out.status, 0) << c.vary;
        EXPECT_NE(out.output.find(c.expected), std::string::npos) << c.vary << ": " << out.output;
        EXPECT_EQ(std::count(out.output.begin(), out.output.end(), '\n'), 1) << c.vary << ": " << out.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "s" / "sweep.csv")) << c.vary;
    }
}

TEST(SweepCli, AutoReferenceIsRenderedOnceAndCachedByContentAndSettings) {
    TempDir dir;
    const std::string sweep = "sweep " + kScene + " --technique volume.raymarch --vary step=1 --reference auto --no-plot -o " +
                              (dir / "s").string();
    ASSERT_EQ(runWeft(sweep).status, 0);
    const auto refs = [&] {
        std::vector<std::filesystem::path> files;
        for (const auto& e : std::filesystem::directory_iterator(dir / "s" / "references")) files.push_back(e.path());
        return files;
    };
    ASSERT_EQ(refs().size(), 1u);
    const auto first = refs().front();
    const auto stamp = std::filesystem::last_write_time(first);
    Metadata md;
    readImage(first.string(), &md);
    std::map<std::string, std::string> meta(md.begin(), md.end());
    EXPECT_EQ(meta["weft:technique"], "volume.raymarch");
    EXPECT_EQ(meta["weft:param:step"], "0.1");
    EXPECT_EQ(meta["weft:spp"], "256");
    ASSERT_EQ(runWeft(sweep + " --vary jitter=true").status, 0);  // another knob: the same reference
    ASSERT_EQ(refs().size(), 1u);
    EXPECT_EQ(std::filesystem::last_write_time(first), stamp);
    ASSERT_EQ(runWeft(sweep + " --seed 9").status, 0);  // another seed: another reference
    EXPECT_EQ(refs().size(), 2u);
}

// The farm form: --list sizes the array, --prepare renders the references,
// each --run K writes one run's file, --merge writes the same tables as the
// sweep run in one process (times aside).
TEST(SweepCli, FarmTasksMergeIntoTheSameTables) {
    TempDir dir;
    const std::string sweep = "sweep " + kScene + " --technique volume.raymarch --vary step=0.5,1 --vary jitter=false,true "
                              "--reference auto --no-plot -o ";
    ASSERT_EQ(runWeft(sweep + (dir / "one").string()).status, 0);
    const std::string farm = (dir / "farm").string();
    const auto list = runWeft(sweep + farm + " --list");
    ASSERT_EQ(list.status, 0) << list.output;
    EXPECT_EQ(list.output.rfind("4 runs\n1 volume.raymarch step=0.5 jitter=false\n", 0), 0u) << list.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "farm"));  // --list writes nothing
    ASSERT_EQ(runWeft(sweep + farm + " --prepare").status, 0);
    for (int k : {4, 2, 1}) ASSERT_EQ(runWeft(sweep + farm + " --run " + std::to_string(k)).status, 0) << k;
    const auto early = runWeft("sweep --merge --no-plot -o " + farm);
    EXPECT_NE(early.status, 0);
    EXPECT_NE(early.output.find("run 3 is missing"), std::string::npos) << early.output;
    ASSERT_EQ(runWeft(sweep + farm + " --run 3").status, 0);
    ASSERT_EQ(runWeft("sweep --merge --no-plot -o " + farm).status, 0);
    EXPECT_EQ(csvWithoutTimes(dir / "one" / "sweep.csv"), csvWithoutTimes(dir / "farm" / "sweep.csv"));
    EXPECT_NE(runWeft(sweep + farm + " --run 5").output.find("the sweep has 4 runs"), std::string::npos);
}

// --prepare renders each run's reference on the scene framed for that run's
// aspect, as a one-process sweep does: the farm's errors are the same.
TEST(SweepCli, FarmPrepareFramesEveryAspect) {
    TempDir dir;
    const std::string sweep = "sweep builtin:sphere --technique volume.raymarch --vary res=24x16,12x16 --reference auto --no-plot -o ";
    ASSERT_EQ(runWeft(sweep + (dir / "one").string()).status, 0);
    const std::string farm = (dir / "farm").string();
    ASSERT_EQ(runWeft(sweep + farm + " --prepare").status, 0);
    for (int k : {1, 2}) ASSERT_EQ(runWeft(sweep + farm + " --run " + std::to_string(k)).status, 0) << k;
    ASSERT_EQ(runWeft("sweep --merge --no-plot -o " + farm).status, 0);
    EXPECT_EQ(csvWithoutTimes(dir / "one" / "sweep.csv"), csvWithoutTimes(dir / "farm" / "sweep.csv"));
}

// A combination the technique refuses (jitter=true with an offset pattern:
// both set the first sample's offset) is recorded with its reason and the
// sweep goes on; the farm's run files and merge keep it; a sweep whose every
// run is refused fails in one line and writes no table.
TEST(SweepCli, ARefusedSettingIsRecordedAndTheSweepGoesOn) {
    TempDir dir;
    const std::string sweep = "sweep " + kScene + " --set offset_pattern=interleaved:4x4 --technique volume.raymarch "
                              "--vary jitter=false,true --vary step=0.5,1 --reference auto --no-plot -o ";
    const auto out = runWeft(sweep + (dir / "s").string());
    ASSERT_EQ(out.status, 0) << out.output;
    EXPECT_NE(out.output.find("4 runs (2 refused"), std::string::npos) << out.output;
    const auto j = readJson(dir / "s" / "sweep.json");
    ASSERT_EQ(j["runs"].size(), 4u);
    for (int i : {0, 1}) {
        EXPECT_FALSE(j["runs"][i].contains("refused")) << i;
        EXPECT_GT(j["runs"][i]["samples"].get<long long>(), 0) << i;
    }
    for (int i : {2, 3}) {
        ASSERT_TRUE(j["runs"][i].contains("refused")) << i;
        EXPECT_NE(j["runs"][i]["refused"].get<std::string>().find("choose one"), std::string::npos) << i;
        EXPECT_FALSE(j["runs"][i].contains("error")) << i;
    }
    std::ifstream csv(dir / "s" / "sweep.csv");
    std::string header, row;
    std::getline(csv, header);
    const auto cells = [](const std::string& line) { return std::count(line.begin(), line.end(), ',') + 1; };
    for (int i = 0; i < 4 && std::getline(csv, row); ++i) {
        EXPECT_EQ(cells(row), cells(header)) << row;
        EXPECT_EQ(row.find("choose one") != std::string::npos, i >= 2) << row;
    }
    std::ifstream md(dir / "s" / "sweep.md");
    const std::string table((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_NE(table.find("- run 3, volume.raymarch jitter=true step=0.5: "), std::string::npos) << table;

    const std::string farm = (dir / "farm").string();
    for (int k : {1, 2, 3, 4}) ASSERT_EQ(runWeft(sweep + farm + " --run " + std::to_string(k)).status, 0) << k;
    ASSERT_EQ(runWeft("sweep --merge --no-plot -o " + farm).status, 0);
    EXPECT_EQ(csvWithoutTimes(dir / "s" / "sweep.csv"), csvWithoutTimes(dir / "farm" / "sweep.csv"));

    const auto all = runWeft("sweep " + kScene + " --set offset_pattern=interleaved:4x4 --technique volume.raymarch "
                             "--vary jitter=true --reference auto --no-plot -o " + (dir / "all").string());
    EXPECT_NE(all.status, 0);
    EXPECT_NE(all.output.find("every run of the sweep was refused"), std::string::npos) << all.output;
    EXPECT_EQ(std::count(all.output.begin(), all.output.end(), '\n'), 1) << all.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "all" / "sweep.csv"));
}

// A volume family's reference converges the volume at 256 spp; on a scene
// with meshes it takes the path tracer's 4096, or the surfaces' light
// sampling noise would stay in every error (docs/trade/smoke_in_cornell/).
TEST(SweepCli, AutoReferenceOnAMeshSceneTakesTheLargestDeclaredSpp) {
    TempDir dir;
    for (const std::string& scene : {std::string("builtin:sphere"), std::string(WEFT_SOURCE_DIR) + "/scenes/cornell.json"}) {
        const auto out = runWeft("sweep " + scene + " --res 4x4 --technique volume.raymarch --vary step=1 --reference auto --no-plot -o " +
                                 (dir / "s").string());
        ASSERT_EQ(out.status, 0) << out.output;
    }
    std::vector<std::string> spps;
    for (const auto& e : std::filesystem::directory_iterator(dir / "s" / "references")) {
        weft::Metadata md;
        readImage(e.path().string(), &md);
        for (const auto& [k, v] : md)
            if (k == "weft:spp") spps.push_back(v);
    }
    std::sort(spps.begin(), spps.end());
    EXPECT_EQ(spps, (std::vector<std::string>{"256", "4096"}));
}
