// weft batch JOBS.json: renders a list of jobs, each a render command line
// written as JSON. Every job is checked (keys, frame ranges, techniques,
// output folders) before the first render; a frame that fails prints its
// error and the others go on; the exit status is 1 when any failed.
//
//   {"jobs": [{"input": "smoke.#.vdb", "output": "out/smoke.#.exr", "frames": "1-10x2",
//              "technique": "volume.raymarch", "set": {"step": 0.5}, "res": "320x240",
//              "spp": 4, "seed": 1, "preview": "out/smoke.#.png", "stats": "out/smoke.#.json",
//              "tile": "1/2", "grid": "density", "threads": 0}]}
// Paths are relative to the current folder, like on the command line.
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "core/base/error.hpp"
#include "core/base/frames.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/render_job.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

using nlohmann::json;

const std::set<std::string> kJobKeys = {"input", "output", "frames", "technique", "set", "res", "spp",
                                        "seed", "preview", "stats", "tile", "grid", "threads"};

std::string text(const json& job, const std::string& key, const std::string& where) {
    if (!job.contains(key)) return "";
    if (!job[key].is_string()) throw Error(where + ": '" + key + "' must be a string");
    return job[key].get<std::string>();
}

std::string scalarText(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

RenderRequest requestOf(const json& job, const std::string& where) {
    if (!job.is_object()) throw Error(where + ": a job must be an object");
    for (const auto& item : job.items())
        if (!kJobKeys.count(item.key())) {
            std::string valid;
            for (const auto& k : kJobKeys) valid += (valid.empty() ? "" : ", ") + k;
            throw Error(where + ": unknown key '" + item.key() + "' (valid: " + valid + ")");
        }
    RenderRequest r;
    r.input = text(job, "input", where), r.output = text(job, "output", where);
    if (r.input.empty() || r.output.empty()) throw Error(where + ": 'input' and 'output' are required");
    r.preview = text(job, "preview", where), r.stats = text(job, "stats", where);
    r.tile = text(job, "tile", where), r.grid = text(job, "grid", where);
    if (job.contains("technique")) r.technique = techniques().get(text(job, "technique", where)).name;
    if (job.contains("res")) r.resolution = text(job, "res", where);
    if (job.contains("spp")) r.spp = job["spp"].get<int>();
    if (job.contains("seed")) r.seed = job["seed"].get<std::uint64_t>();
    if (job.contains("threads")) r.threads = job["threads"].get<int>();
    if (job.contains("set")) {
        if (!job["set"].is_object()) throw Error(where + ": 'set' must be an object of key: value");
        for (const auto& item : job["set"].items()) r.sets.push_back(item.key() + "=" + scalarText(item.value()));
    }
    if (!r.tile.empty()) parseTileSpec(r.tile);
    if (r.resolution) parseResolution(*r.resolution);
    return r;
}

std::vector<RenderRequest> loadBatch(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error("batch '" + path + "': cannot be read");
    json doc;
    try {
        doc = json::parse(in);
    } catch (const json::exception& e) {
        throw Error("batch '" + path + "': " + e.what());
    }
    if (!doc.is_object() || !doc.contains("jobs") || !doc["jobs"].is_array() || doc["jobs"].empty())
        throw Error("batch '" + path + "': expected {\"jobs\": [ {...}, ... ]}");
    std::vector<RenderRequest> all;
    for (std::size_t i = 0; i < doc["jobs"].size(); ++i) {
        const std::string where = "batch '" + path + "' job " + std::to_string(i + 1);
        try {
            const json& job = doc["jobs"][i];
            const RenderRequest r = requestOf(job, where);
            const std::string frames = text(job, "frames", where);
            for (RenderRequest& q : frames.empty() ? std::vector<RenderRequest>{r} : requestsForFrames(r, parseFrameRange(frames)))
                all.push_back(std::move(q));
        } catch (const json::exception& e) {
            throw Error(where + ": " + e.what());
        } catch (const Error& e) {
            const std::string msg = e.what();
            throw Error(msg.rfind("batch '", 0) == 0 ? msg : where + ": " + msg);
        }
    }
    return all;
}

const CommandRegistrar registrar{{"batch", 16, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("batch", "render the jobs of a JSON batch file (frames, techniques, outputs)");
    auto path = std::make_shared<std::string>();
    cmd->add_option("jobs", *path, "batch .json: {\"jobs\": [{\"input\", \"output\", \"frames\", ...}]}")->required();
    cmd->callback([path] {
        if (runRenders(loadBatch(*path)) > 0) commandExitStatus() = 1;
    });
}}};

}  // namespace

}  // namespace weft
