#include "plugins/host/render_job.hpp"

#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "core/base/files/atomic_file.hpp"
#include "core/base/options/frames.hpp"
#include "core/base/files/input_file.hpp"
#include "core/base/memory/physical_memory.hpp"
#include "core/scene/scene.hpp"
#include "core/scene/scene_budget.hpp"
#include "plugins/host/command.hpp"
#include "plugins/host/command_line_monitor.hpp"
#include "plugins/host/render_cli.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

const Counter kImageNonfinite{"image.nonfinite", "NaN/Inf values written as 0 (a technique bug when not 0)"};

// Two outputs naming one file would leave only the last written: the render
// replaced by its statistics, say.
void checkDistinctOutputs(const RenderRequest& r) {
    const std::pair<const char*, const std::string*> named[] = {{"-o", &r.output}, {"--preview", &r.preview}, {"--stats", &r.stats}};
    for (std::size_t i = 0; i < std::size(named); ++i)
        for (std::size_t j = i + 1; j < std::size(named); ++j) {
            if (named[i].second->empty() || named[j].second->empty()) continue;
            std::error_code ec;
            const auto a = std::filesystem::weakly_canonical(*named[i].second, ec), b = std::filesystem::weakly_canonical(*named[j].second, ec);
            if (a == b || sameExistingFile(*named[i].second, *named[j].second))
                throw Error(std::string(named[j].first) + " names the same file as " + named[i].first + " ('" + *named[j].second +
                            "'); each output needs its own file");
        }
}

void checkOutputs(const RenderRequest& r) {
    if (!r.output.empty()) {
        checkOutputPath(r.output, "output");
        if (!(r.output.size() > 4 && r.output.compare(r.output.size() - 4, 4, ".exr") == 0))
            throw Error("output '" + r.output + "': the render output must be an .exr file (use --preview for PNG)");
    }
    if (!r.preview.empty()) {
        checkOutputPath(r.preview, "preview");
        if (!isPreviewPath(r.preview)) throw Error("preview '" + r.preview + "': expected a .png, .jpg or .tif file");
    }
    if (!r.stats.empty()) checkOutputPath(r.stats, "stats", OutputKind::Text);
    checkDistinctOutputs(r);
}

// Once the scene has loaded, every file it read is known: no output may be one.
void refuseInputsAsOutputs(const RenderRequest& r) {
    if (!r.output.empty()) refuseInputAsOutput(r.output, "output");
    if (!r.preview.empty()) refuseInputAsOutput(r.preview, "preview");
    if (!r.stats.empty()) refuseInputAsOutput(r.stats, "stats");
}

RenderSettings settingsFor(const EffectiveRender& q) {
    RenderSettings s;
    s.width = q.resolution.width, s.height = q.resolution.height;
    s.spp = q.spp;
    s.seed = q.seed;
    return s;
}

// Replaces NaN/Inf by 0 (a last guard: techniques must not produce them) and counts them.
std::int64_t scrubNonFinite(Image& image) {
    std::int64_t bad = 0;
    for (float& v : image.data())
        if (!std::isfinite(v)) v = 0.0f, ++bad;
    return bad;
}

Metadata metadataFor(const RenderRequest& r, const std::string& technique, const ParamSet& params,
                     const RenderSettings& s, const CounterMap& counters) {
    Metadata md{{"weft:version", WEFT_VERSION}, {"weft:input", r.input}, {"weft:technique", technique},
                {"weft:seed", std::to_string(s.seed)}, {"weft:spp", std::to_string(s.spp)}};
    for (const auto& [k, v] : params.values()) md.emplace_back("weft:param:" + k, v);
    for (const auto& [k, v] : counters) md.emplace_back("weft:counter:" + k, std::to_string(v));
    return md;
}

// Tile metadata: merge checks a set against it, and places each band.
void addTileMetadata(Metadata& md, const TileSpec& tile, const ImageWindow& w, int width, int height) {
    md.emplace_back("weft:tile", tile.text());
    md.emplace_back("weft:tile:full_resolution", std::to_string(w.fullWidth) + "x" + std::to_string(w.fullHeight));
    md.emplace_back("weft:tile:data_window", std::to_string(w.x) + " " + std::to_string(w.y) + " " +
                                                 std::to_string(w.x + width - 1) + " " + std::to_string(w.y + height - 1));
}

// The rows [y0, y1) of an image, all channels.
Image cropRows(const Image& full, int y0, int y1) {
    Image band(full.width(), y1 - y0, full.channelNames());
    const std::size_t rowFloats = std::size_t(full.width()) * full.channelCount();
    std::copy(full.data().begin() + std::ptrdiff_t(y0 * rowFloats), full.data().begin() + std::ptrdiff_t(y1 * rowFloats),
              band.data().begin());
    return band;
}

void writeStats(const RenderRequest& r, const RenderOutcome& out, int threads) {
    nlohmann::ordered_json j;
    for (const auto& [k, v] : out.metadata) {
        if (k.rfind("weft:param:", 0) == 0) j["params"][k.substr(11)] = v;
        else if (k.rfind("weft:counter:", 0) != 0 && k != "weft:complete") j[k.substr(5)] = v;
    }
    j["resolution"] = {out.image.width(), out.image.height()};
    j["threads"] = threads;
    j["counters"] = nlohmann::ordered_json::object();
    for (const auto& [k, v] : out.counters) j["counters"][k] = v;
    for (const auto& [k, v] : out.timingsMs) j["timings_ms"][k] = v;
    writeTextAtomically(r.stats, j.dump(2) + "\n", "stats");
}

// A library's exception leaves a stage as a weft::Error that says which
// stage of which input failed; running out of memory says what to try.
template <typename F>
auto inStage(const std::string& stage, F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const Error&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw Error(stage + ": out of memory (try a smaller --res, fewer samples or a coarser grid; "
                    "--max-memory GiB refuses renders above a limit before they start)");
    } catch (const std::filesystem::filesystem_error& e) {
        throw Error(stage + ": '" + e.path1().string() + "': " + e.code().message());
    } catch (const std::exception& e) {
        throw Error(stage + ": " + e.what());
    }
}

}  // namespace

int effectiveThreads(int requested) {
    return requested > 0 ? requested : int(std::max(1u, std::thread::hardware_concurrency()));
}

double physicalMemoryGiB() { return physicalMemoryBytes() / double(1 << 30); }

// What a render needs: the technique's working memory per pixel and the
// scene already loaded (grids and meshes). Refused before the technique
// allocates anything when it exceeds the limit.
static double memoryLimitBytes(const RenderRequest& r) {
    return (r.maxMemoryGiB > 0 ? r.maxMemoryGiB : 0.75 * physicalMemoryGiB()) * double(1 << 30);
}

void checkMemory(const RenderRequest& r, int width, int height, const std::string& technique, double sceneBytes) {
    const double limit = memoryLimitBytes(r) / double(1 << 30);
    const double perPixel = techniques().has(technique) ? techniques().get(technique).bytesPerPixel : 32;  // unknown: refused later
    const double gib = double(1 << 30), image = double(width) * double(height) * perPixel / gib, need = image + sceneBytes / gib;
    if (need > limit) {
        char text[320];
        std::snprintf(text, sizeof text, "a %dx%d render with %s needs about %.3g GiB (%.0f bytes per pixel for its image and "
                      "buffers, %.3g GiB of scene), above the %.3g GiB limit (--max-memory GiB; the default is 3/4 of physical memory)",
                      width, height, technique.c_str(), need, perPixel, sceneBytes / gib, limit);
        throw Error(text);
    }
}

// Bytes the loaded scene holds: its grids' trees and its meshes' triangles
// (vertices, indices and a BVH of about 64 bytes per triangle).
double sceneBytes(const Scene& scene) {
    double bytes = 0;
    std::set<const void*> trees;  // volumes placed from one file share its tree
    for (const Volume& v : scene.volumes)
        if (trees.insert(&v.grid->tree()).second) bytes += double(v.grid->memUsage());
    for (const auto& m : scene.meshes) bytes += double(m.triangleCount()) * (3 * 12 + 12 + 64);
    return bytes;
}

void validateRequest(const RenderRequest& r) {
    // Requests built in code (tests, chains, Python) have not been through the table.
    if (r.tile) requireValid(*r.tile);
    checkRenderNumber("threads", r.threads);
    checkRenderNumber("max-memory", r.maxMemoryGiB);
    if (r.spp) checkRenderNumber("spp", *r.spp);
    // Against the table's range exactly, not through a double (2^53 + 1 would read as 2^53).
    if (const RenderOption* seed = findRenderOption("seed", kOnCommandLine); r.seed && seed) {
        const std::string text = std::to_string(*r.seed);
        if (integerOutOfRange(text, seed->spec)) throw Error(commandLineLabel(*seed) + " " + text + " is outside " + seed->spec.allowedText());
    }
    if (r.resolution) {
        requireValid(*r.resolution);
        checkMemory(r, r.resolution->width, r.resolution->height, r.technique.value_or(defaultTechnique(r.sets)), 0);
    }
    std::map<std::string, std::string> given;
    for (const std::string& kv : r.sets) given.insert(splitKeyValue(kv, "--set"));
    // Scene files, meshes and built-in scenes may name a technique of their
    // own: their parameters are checked once the scene is loaded.
    const bool bareVdb = r.input.size() > 4 && r.input.compare(r.input.size() - 4, 4, ".vdb") == 0;
    if (r.technique || bareVdb) techniques().get(r.technique.value_or(defaultTechnique(r.sets))).params.parse(given);
}

std::optional<double> requestAspect(const RenderRequest& r) {
    if (!r.resolution) return std::nullopt;
    requireValid(*r.resolution);  // a zero height would divide by zero
    return double(r.resolution->width) / r.resolution->height;
}

LoadedScene loadRequestScene(const RenderRequest& r) {
    const auto t0 = std::chrono::steady_clock::now();
    LoadedScene loaded;
    loaded.scene = std::make_shared<const Scene>(
        inStage("loading '" + r.input + "'", [&] { return loadSceneWithin(r.input, requestAspect(r), r.grid, r.frame, memoryLimitBytes(r)); }));
    loaded.loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return loaded;
}

RenderOutcome renderToImage(const RenderRequest& r, const std::function<void()>& afterLoad) {
    validateRequest(r);  // cheap checks fail before the scene loads
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, effectiveThreads(r.threads));
    const LoadedScene loaded = loadRequestScene(r);
    if (afterLoad) afterLoad();
    return renderLoadedScene(r, loaded);
}

CheckedRender checkRender(const RenderRequest& r, const Scene& scene) {
    CheckedRender c{effectiveRender(r, scene.render), {}};  // the one precedence rule
    const EffectiveRender& q = c.effective;
    checkRenderNumber("spp", q.spp);  // requests built in code skip the table
    checkMemory(r, q.resolution.width, q.resolution.height, q.technique, sceneBytes(scene));  // the scene's own resolution and technique
    const TechniqueInfo& info = techniques().get(q.technique);
    std::map<std::string, std::string> given;
    for (const std::string& kv : q.sets) {
        auto [k, v] = splitKeyValue(kv, "--set");
        given[k] = v;
    }
    c.params = info.params.parse(given);
    checkTechniqueContent(info, scene);
    if (scene.cameraMoves() && !info.motionBlur)
        throw Error("the camera moves while the shutter is open, and " + info.name + " renders one instant: use " +
                    techniquesWith([](const TechniqueInfo& t) { return t.motionBlur; }) + " for motion blur, or camera.shutter [0, 0]");
    if (!info.motionBlur && !info.velocityBlur)
        requireStillVolumes(scene, info.name, techniquesWith([](const TechniqueInfo& t) { return t.motionBlur || t.velocityBlur; }));
    if (!info.scatters) requireNoColorGrids(scene, info.name, techniquesWith([](const TechniqueInfo& t) { return t.scatters; }));
    if (!info.emission) requireNoEmission(scene, info.name, techniquesWith([](const TechniqueInfo& t) { return t.emission; }));
    return c;
}

RenderOutcome renderLoadedScene(const RenderRequest& r, const LoadedScene& loaded) {
    const RenderRunning running;  // on the command line, a signal now interrupts the render instead of ending weft
    RenderMonitor* monitor = r.monitor ? r.monitor : &commandLineMonitor();
    const Scene& scene = *loaded.scene;
    RenderContext ctx;
    ctx.timings.add("load", loaded.loadMs);
    ctx.timings.monitor = monitor;
    const CheckedRender checked = checkRender(r, scene);
    const EffectiveRender& q = checked.effective;
    const ParamSet& params = checked.params;
    ctx.settings = settingsFor(q);
    ctx.settings.monitor = monitor;
    RowBand band{0, ctx.settings.height};
    if (r.tile) {
        band = tileRows(ctx.settings.height, r.tile->index, r.tile->count);
        ctx.settings.rowBegin = band.begin, ctx.settings.rowEnd = band.end;
    }
    const std::string name = q.technique;
    const TechniqueInfo& info = techniques().get(name);
    char stage[160];
    std::snprintf(stage, sizeof stage, "%s at %dx%d", name.c_str(), ctx.settings.width, ctx.settings.height);
    // A technique may build per-scene structures before its render (the
    // raymarch's empty-space cells, a dense copy): timed as "setup".
    std::unique_ptr<Technique> technique;
    {
        ScopedTimer timer(ctx.timings, "setup");
        technique = inStage(stage, [&] { return info.create(scene, params); });
    }
    for (const Volume& v : scene.volumes)
        if (v.gridsPicked) std::fprintf(stderr, "weft: %s: grids found by their names: %s\n", v.source.c_str(), v.grids.c_str());
    if (const std::string unused = info.scatters ? "" : unusedColorGrids(scene, name); !unused.empty())
        std::fprintf(stderr, "weft: warning: %s\n", unused.c_str());

    RenderOutcome out;
    {
        ScopedTimer timer(ctx.timings, "render");
        out.image = inStage(stage, [&] { return technique->render(scene, ctx); });
    }
    throwIfInterrupted(monitor);  // interrupted after its last poll: still nothing is written
    if (std::int64_t bad = scrubNonFinite(out.image)) {
        ctx.counters.add(kImageNonfinite, bad);
        std::fprintf(stderr, "weft: warning: %s produced %lld NaN/Inf values (written as 0)\n", name.c_str(), (long long)bad);
    }
    out.window = ImageWindow{0, band.begin, out.image.width(), out.image.height()};
    if (r.tile) out.image = cropRows(out.image, band.begin, band.end);
    out.counters = ctx.counters.merged();
    out.metadata = metadataFor(r, name, params, ctx.settings, out.counters);
    if (r.frame) out.metadata.emplace_back("weft:frame", std::to_string(*r.frame));
    for (std::size_t i = 0; i < scene.volumes.size(); ++i) {  // what each role of an emitting or moving volume read
        const Volume& v = scene.volumes[i];
        const std::string key = "weft:volume:" + std::to_string(i);
        if (v.emission || v.motion) out.metadata.emplace_back(key + ":grids", v.grids);
        if (v.motion) out.metadata.emplace_back(key + ":motion_reach_voxels", formatNumber(v.motionReach));
    }
    if (!scene.shutter.instant())
        out.metadata.emplace_back("weft:shutter", formatNumber(scene.shutter.open) + " " + formatNumber(scene.shutter.close));
    if (r.tile) addTileMetadata(out.metadata, *r.tile, out.window, out.image.width(), out.image.height());
    out.metadata.emplace_back("weft:complete", "1");
    out.timingsMs = ctx.timings.entries();
    return out;
}

// The EXR's encoding from --compression and -d, recorded in its metadata; a
// -d CHANNEL=TYPE that names none of this image's channels is a warning (the
// same command line may serve techniques with other AOVs).
ExrEncoding exrEncodingFor(const RenderRequest& r, RenderOutcome& out) {
    ExrEncoding e{r.compression.empty() ? kDefaultExrCompression : r.compression, r.pixelTypes, effectiveThreads(r.threads)};
    std::vector<std::string> unmatched;
    const std::vector<bool> half = halfChannels(out.image.channelNames(), e.pixelTypes, &unmatched);
    for (const std::string& spec : unmatched)
        std::fprintf(stderr, "weft: warning: -d '%s' names no channel of the image (%zu channels)\n", spec.c_str(), half.size());
    out.metadata.emplace_back("weft:compression", e.compression);
    out.metadata.emplace_back("weft:pixel_types", pixelTypesText(out.image.channelNames(), half));
    return e;
}

RenderOutcome runRender(const RenderRequest& r) {
    const InputJob job;  // the files this render reads, which its outputs must not replace
    checkOutputs(r);
    RenderOutcome out = renderToImage(r, [&] { refuseInputsAsOutputs(r); });
    const auto t0 = std::chrono::steady_clock::now();
    if (!r.output.empty()) {
        const ExrEncoding encoding = exrEncodingFor(r, out);
        writeExr(out.image, r.output, out.metadata, out.window, encoding);
    }
    if (!r.preview.empty()) writePreview(out.image, r.preview);
    out.timingsMs.emplace_back("write", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    if (!r.stats.empty()) writeStats(r, out, effectiveThreads(r.threads));
    if (r.verbose) {
        std::printf("%s -> %s (%dx%d)\ncounters:\n%s", r.input.c_str(), r.output.c_str(), out.image.width(),
                    out.image.height(), Counters::table(out.counters).c_str());
        std::printf("timings:\n");
        for (const auto& [k, v] : out.timingsMs) std::printf("  %-24s %12.1f ms\n", k.c_str(), v);
    }
    return out;
}

std::vector<RenderRequest> requestsForFrames(const RenderRequest& r, const std::vector<int>& frames) {
    if (frames.size() > 1) {
        const std::pair<const char*, const std::string*> named[] = {{"output", &r.output}, {"preview", &r.preview}, {"stats", &r.stats}};
        for (const auto& [what, name] : named)
            if (!name->empty() && !hasFrameWildcard(*name))
                throw Error(std::string(what) + " '" + *name + "' has no frame number (# = 4 digits, @ = 1 digit, e.g. out.#.exr) for " +
                            std::to_string(frames.size()) + " frames");
    }
    std::vector<RenderRequest> out;
    for (int f : frames) {
        RenderRequest q = r;
        q.frame = f;
        for (std::string* name : {&q.input, &q.output, &q.preview, &q.stats}) *name = expandFrameName(*name, f);
        out.push_back(std::move(q));
    }
    return out;
}

int runRenders(const std::vector<RenderRequest>& requests, const AfterRender& after) {
    for (const RenderRequest& q : requests) checkOutputs(q);  // unwritable outputs fail before any render
    int failed = 0;
    for (const RenderRequest& q : requests) {
        try {
            RenderOutcome out = runRender(q);
            if (after) after(q, out);
        } catch (const Cancelled&) {
            throw;  // the whole command stops, not only this frame
        } catch (const std::exception& e) {
            ++failed;
            const std::string frame = q.frame ? "frame " + std::to_string(*q.frame) + ": " : "";
            std::fprintf(stderr, "weft: error: %s%s\n", frame.c_str(), printableLine(e.what()).c_str());
        }
    }
    if (failed && requests.size() > 1)
        std::fprintf(stderr, "weft: %d of %zu renders failed\n", failed, requests.size());
    return failed;
}

}  // namespace weft
