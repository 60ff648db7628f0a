// Chain steps that act on the image an earlier step left (see chain.hpp):
//   exposure STOPS   scale R, G, B by 2^STOPS (scene-linear; alpha and AOVs kept)
//   preview FILE     write a display-referred PNG/JPEG/TIFF through OpenColorIO
//   write FILE.exr   write the image as EXR with the render's metadata and the steps applied
#include <cmath>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "plugins/command.hpp"
#include "plugins/host/chain.hpp"

namespace weft {

ChainState& chainState() {
    static ChainState state;
    return state;
}

ChainImage& chainInput(const std::string& step) {
    auto& current = chainState().current;
    if (!current) throw Error("'" + step + "' needs an image: put it after a render on the same command line");
    return *current;
}

namespace {

std::string joined(const std::vector<std::string>& steps) {
    std::string out;
    for (const std::string& s : steps) out += (out.empty() ? "" : " | ") + s;
    return out;
}

void applyExposure(double stops) {
    if (!std::isfinite(stops) || std::abs(stops) > 64) throw Error("exposure " + std::to_string(stops) + ": expected stops in [-64, 64]");
    ChainImage& in = chainInput("exposure");
    const float scale = float(std::exp2(stops));
    for (const char* name : {"R", "G", "B"}) {
        const int c = in.image.channelIndex(name);
        if (c < 0) continue;
        for (int y = 0; y < in.image.height(); ++y)
            for (int x = 0; x < in.image.width(); ++x) in.image.at(x, y, c) *= scale;
    }
    char text[64];
    std::snprintf(text, sizeof text, "exposure %g", stops);
    in.steps.emplace_back(text);
}

void writePreviewStep(const std::string& path) {
    ChainImage& in = chainInput("preview");
    checkOutputPath(path, "preview");
    if (!isPreviewPath(path)) throw Error("preview '" + path + "': expected a .png, .jpg or .tif file");
    writePreview(in.image, path);
    chainState().wroteFile = true;
}

void writeExrStep(const std::string& path) {
    ChainImage& in = chainInput("write");
    checkOutputPath(path, "write");
    Metadata md;
    for (const auto& kv : in.metadata)
        if (kv.first != "weft:complete") md.push_back(kv);
    if (!in.steps.empty()) md.emplace_back("weft:chain", joined(in.steps));
    md.emplace_back("weft:complete", "1");
    writeExr(in.image, path, md, in.window);
    chainState().wroteFile = true;
}

const CommandRegistrar exposure{{"exposure", 40, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("exposure", "chain step: scale R, G, B of the previous result by 2^STOPS");
    auto stops = std::make_shared<double>(0.0);
    cmd->add_option("stops", *stops, "exposure change in stops (+1 doubles)")->required();
    cmd->callback([stops] { applyExposure(*stops); });
    cmd->immediate_callback();
}}};

const CommandRegistrar preview{{"preview", 41, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("preview", "chain step: write the previous result as a display-referred PNG/JPEG");
    auto path = std::make_shared<std::string>();
    cmd->add_option("file", *path, "preview file (.png, .jpg, .tif)")->required();
    cmd->callback([path] { writePreviewStep(*path); });
    cmd->immediate_callback();
}}};

const CommandRegistrar write{{"write", 42, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("write", "chain step: write the previous result as EXR with its metadata");
    auto path = std::make_shared<std::string>();
    cmd->add_option("file", *path, "output .exr")->required();
    cmd->callback([path] { writeExrStep(*path); });
    cmd->immediate_callback();
}}};

}  // namespace

}  // namespace weft
