// weft batch JOBS.json: renders a list of jobs, each a render command line
// written as JSON. Every job is checked (keys, frame ranges, techniques,
// output folders) before the first render; a frame that fails prints its
// error and the others go on; the exit status is 1 when any failed.
//
//   {"jobs": [{"input": "smoke.#.vdb", "output": "out/smoke.#.exr", "frames": "1-10x2",
//              "technique": "volume.raymarch", "set": {"step": 0.5}, "res": "320x240",
//              "spp": 4, "seed": 1, "preview": "out/smoke.#.png", "stats": "out/smoke.#.json",
//              "tile": "1/2", "grid": "density", "threads": 0}]}
// The keys are those of `weft help options` (res for resolution, set or params);
// paths are relative to the current folder, like on the command line.
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/base/error.hpp"
#include "core/base/options/frames.hpp"
#include "core/base/files/input_file.hpp"
#include "core/base/options/render_options.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/render_job.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

using nlohmann::json;

// A job's keys are the render options' names (core/base/options/render_options.hpp),
// read and checked by the same table as the command line; then the checks a
// command line gets before any render (technique, --set keys, memory).
RenderRequest requestOf(const json& job, const std::string& where) {
    if (!job.is_object()) throw Error(where + ": a job must be an object");
    RenderRequest r;
    readRenderOptions(r, job, [&](const std::string&, const std::string& msg) { throw Error(where + ": " + msg); });
    if (r.input.empty() || r.output.empty()) throw Error(where + ": 'input' and 'output' are required");
    if (r.technique) r.technique = techniques().get(*r.technique).name;
    validateRequest(r);
    return r;
}

std::vector<RenderRequest> loadBatch(const std::string& path) {
    requireRegularFile(path, "batch");  // a FIFO would block the read forever
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
            for (RenderRequest& q : !r.frames ? std::vector<RenderRequest>{r} : requestsForFrames(r, *r.frames))
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
