// Chain steps (plugins/host/chain.hpp) that act on the image an earlier step left:
//   exposure STOPS          scale R, G, B by 2^STOPS (scene-linear; alpha and AOVs kept)
//   colorconvert FROM TO    OpenColorIO colour-space conversion of R, G, B (core/image/color.hpp)
//   preview FILE            write a display-referred PNG/JPEG/TIFF through OpenColorIO
//   write FILE.exr          write the image as EXR with the render's metadata and the steps applied
// (`atrous`, the A-Trous filter step, lives with the filter: plugins/filter_atrous.)
#include <cmath>

#include "core/base/files/atomic_file.hpp"
#include "core/image/color.hpp"
#include "core/base/error.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/chain.hpp"

namespace weft {

namespace {

std::string joined(const std::vector<std::string>& steps) {
    std::string out;
    for (const std::string& s : steps) out += (out.empty() ? "" : " | ") + s;
    return out;
}

void applyExposure(ChainImage& in, double stops) {
    const float scale = float(std::exp2(stops));
    for (const char* name : {"R", "G", "B"}) {
        const int c = in.image.channelIndex(name);
        if (c < 0) continue;
        for (int y = 0; y < in.image.height(); ++y)
            for (int x = 0; x < in.image.width(); ++x) in.image.at(x, y, c) *= scale;
    }
}

void writeExrStep(ChainImage& in, const std::string& path) {
    Metadata md;
    for (const auto& kv : in.metadata)
        if (kv.first != "weft:complete") md.push_back(kv);
    if (!in.steps.empty()) md.emplace_back("weft:chain", joined(in.steps));
    md.emplace_back("weft:complete", "1");
    writeExr(in.image, path, md, in.window);
}

std::string formatStops(double stops) {
    char text[64];
    std::snprintf(text, sizeof text, "exposure %g", stops);
    return text;
}

const CommandRegistrar exposure{{"exposure", 40, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("exposure", "chain step: scale R, G, B of the previous result by 2^STOPS");
    auto stops = std::make_shared<double>(0.0);
    cmd->add_option("stops", *stops, "exposure change in stops (+1 doubles)")->required();
    cmd->callback([stops] {
        const double v = *stops;
        if (!std::isfinite(v) || std::abs(v) > 64) throw Error("exposure " + std::to_string(v) + ": expected stops in [-64, 64]");
        addChainStep({"exposure", std::nullopt, [v](ChainImage& in) {
            applyExposure(in, v);
            in.steps.push_back(formatStops(v));
        }});
    });
    cmd->immediate_callback();
}}};

const CommandRegistrar colorconvert{{"colorconvert", 41, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("colorconvert", "chain step: convert R, G, B of the previous result between OpenColorIO colour spaces");
    auto spaces = std::make_shared<std::pair<std::string, std::string>>();
    cmd->add_option("from", spaces->first, "source colour space (weft renders lin_rec709, the scene_linear role)")->required();
    cmd->add_option("to", spaces->second, "target colour space, e.g. acescg")->required();
    cmd->callback([spaces] {
        auto conversion = std::shared_ptr<const ColorConversion>(colorConversion(spaces->first, spaces->second));
        const std::string text = "colorconvert " + spaces->first + " " + spaces->second;
        addChainStep({"colorconvert", std::nullopt, [conversion, text](ChainImage& in) {
            conversion->apply(in.image);
            in.steps.push_back(text);
        }});
    });
    cmd->immediate_callback();
}}};

const CommandRegistrar preview{{"preview", 42, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("preview", "chain step: write the previous result as a display-referred PNG/JPEG");
    auto path = std::make_shared<std::string>();
    cmd->add_option("file", *path, "preview file (.png, .jpg, .tif); # or @ = frame number")->required();
    cmd->callback([path] {
        if (!isPreviewPath(*path)) throw Error("preview '" + *path + "': expected a .png, .jpg or .tif file");
        addChainStep({"preview", *path, [p = *path](ChainImage& in) { writePreview(in.image, framePath(p, in)); }});
    });
    cmd->immediate_callback();
}}};

const CommandRegistrar write{{"write", 43, [](CLI::App& app) {
    auto* cmd = app.add_subcommand("write", "chain step: write the previous result as EXR with its metadata");
    auto path = std::make_shared<std::string>();
    cmd->add_option("file", *path, "output .exr; # or @ = frame number")->required();
    cmd->callback([path] {
        if (!(path->size() > 4 && path->compare(path->size() - 4, 4, ".exr") == 0))
            throw Error("write '" + *path + "': expected an .exr file (use preview for PNG)");
        addChainStep({"write", *path, [p = *path](ChainImage& in) { writeExrStep(in, framePath(p, in)); }});
    });
    cmd->immediate_callback();
}}};

}  // namespace

}  // namespace weft
