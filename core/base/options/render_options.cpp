#include "core/base/options/render_options.hpp"

#include <cctype>
#include <nlohmann/json.hpp>

#include "core/base/error.hpp"
#include "core/base/options/frames.hpp"
#include "core/base/options/exr_options.hpp"
#include "core/base/options/param_value.hpp"

namespace weft {

namespace {

using nlohmann::json;

constexpr unsigned kEverywhere = kOnCommandLine | kInBatchJob | kInScene;

// Checks for string options: each throws a message that starts with the value.
void checkResolution(const std::string& t) {
    if (!readResolution(t)) throw Error("'" + t + "': expected WxH with W and H in [1, 65536], e.g. 512x512");
}
void checkKeyValue(const std::string& t) {
    const auto eq = t.find('=');
    if (eq == std::string::npos || eq == 0) throw Error("'" + t + "': expected key=value");
}
void checkFrames(const std::string& t) {
    if (t.find_first_not_of(" \t") == std::string::npos)
        throw Error("'" + t + "' is empty: give frames such as 1001-1100, 1,3,5-9 or 7");
    parseFrameRange(t);
}
void checkTile(const std::string& t) {
    if (!t.empty()) parseTileSpec(t);
}

RenderOption option(ParamSpec spec, unsigned places, void (*store)(RenderRequest&, const std::string&)) {
    RenderOption o;
    o.spec = std::move(spec), o.places = places, o.store = store;
    return o;
}

// An option a scene's render block may give too.
RenderOption sceneOption(ParamSpec spec, void (*store)(SceneRender&, const std::string&), std::vector<std::string> aliases = {}) {
    RenderOption o;
    o.spec = std::move(spec), o.places = kEverywhere, o.storeInScene = store, o.aliases = std::move(aliases);
    return o;
}

std::vector<RenderOption> makeTable() {
    constexpr unsigned kRequestOnly = kOnCommandLine | kInBatchJob;
    std::vector<RenderOption> t;
    t.push_back(option(stringParam("input", "", "scene .json, .vdb, .obj/.ply file, or builtin:NAME; # or @ = frame number"),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) { r.input = v; }));
    t.push_back(option(stringParam("output", "", "output EXR (RGBA + AOVs + metadata); # or @ = frame number"),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) { r.output = v; }));
    t.push_back(option(stringParam("preview", "", "also write a display-referred PNG/JPEG through OpenColorIO"),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) { r.preview = v; }));
    t.push_back(option(stringParam("stats", "", "write counters, timings and parameters as JSON"),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) { r.stats = v; }));
    t.push_back(option(stringParam("frames", "", "frames to render, e.g. 1001-1100x2, 1,3,5-9, -5--1 (names need # or @)", checkFrames),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) { r.frames = parseFrameRange(v); }));
    t.push_back(option(stringParam("tile", "", "render only tile i of n (1-based row bands), e.g. 2/4; merge with `weft merge`", checkTile),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) {
                           // "" is the whole image, as checkTile lets it through
                           r.tile = v.empty() ? std::nullopt : std::optional(parseTileSpec(v));
                       }));
    t.push_back(option(stringParam("grid", "", "grid of a bare .vdb (default: density, else the first float grid)"),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) { r.grid = v; }));
    t.push_back(sceneOption(stringParam("technique", "volume.raymarch",
                                        "technique (weft help lists them); volume.singlescatter with set compat=vdb_render"),
                            [](SceneRender& r, const std::string& v) { r.technique = v; }));
    t.push_back(sceneOption(stringParam("set", "", "technique parameter key=value, repeatable (weft help TECHNIQUE)", checkKeyValue),
                            [](SceneRender& r, const std::string& v) { r.sets.push_back(v); }, {"params"}));
    t.back().repeated = true;
    t.push_back(sceneOption(stringParam("resolution", "512x512", "image size WxH ([W, H] in JSON)", checkResolution),
                            [](SceneRender& r, const std::string& v) { r.resolution = parseResolution(v); }, {"res"}));
    t.push_back(sceneOption(intParam("spp", 1, 1, 1 << 20, "camera samples per pixel"),
                            [](SceneRender& r, const std::string& v) { r.spp = int(std::stoll(v)); }));
    t.push_back(sceneOption(intParam("seed", 0, 0, std::int64_t(1) << 53, "random seed (same seed, same image)"),
                            [](SceneRender& r, const std::string& v) { r.seed = std::uint64_t(std::stoull(v)); }));
    t.push_back(option(intParam("threads", 0, 0, 4096, "worker threads, 0 = all cores (the image does not depend on it)"),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) { r.threads = int(std::stoll(v)); }));
    t.push_back(option(floatParam("max-memory", 0, 0, 1e6, "refuse renders estimated to need more GiB than this: the technique's buffers per pixel and the scene (0 = 3/4 of physical memory)"),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) { r.maxMemoryGiB = std::stod(v); }));
    t.push_back(option(enumParam("compression", kDefaultExrCompression, exrCompressionNames(),
                                 "EXR compression; lossless: none, rle, zips, zip, piz; lossy: pxr24 (floats rounded to 24 bits), "
                                 "b44, b44a (lossy on half channels), dwaa, dwab (lossy on R, G, B, Y, and on a layer's .R/.G/.B/.Y such as N.Y)"),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) { r.compression = v; }));
    t.push_back(option(stringParam("pixel_type", "float",
                                   "EXR pixel type, repeatable, later ones win: half or float for every channel, or CHANNEL=TYPE "
                                   "for a channel, a layer (N: N.X, N.Y, N.Z) or aovs (all but R, G, B, A); half saturates at 65504",
                                   checkPixelTypeSpec),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) { r.pixelTypes.push_back(v); }));
    t.back().repeated = true;
    t.push_back(option(boolParam("verbose", false, "print the counter table and timings"),
                       kRequestOnly, [](RenderRequest& r, const std::string& v) { r.verbose = v == "true"; }));
    return t;
}

// The value in canonical text, or an Error whose message starts with the value.
std::string checked(const ParamSpec& spec, const std::string& text) {
    const ParamValue v = checkParamValue(spec, text);
    switch (v.fault) {
        case ParamValue::Fault::None: return v.canonical;
        case ParamValue::Fault::NotBool: throw Error("'" + text + "' is not true or false");
        case ParamValue::Fault::NotNumber: throw Error("'" + text + "' is not a number");
        case ParamValue::Fault::NotInteger: throw Error("'" + text + "' is not an integer");
        case ParamValue::Fault::OutOfRange: throw Error(text + " is outside " + spec.allowedText());
        case ParamValue::Fault::NotChoice: throw Error("'" + text + "' is not " + spec.allowedText());
        case ParamValue::Fault::Check: throw Error(v.checkMessage);
    }
    throw Error("'" + text + "' is not " + spec.allowedText());
}

// "LABEL 'v': why" when the message starts with the value, else "LABEL: message".
std::string labelled(const std::string& label, const std::string& message) {
    const bool startsWithValue = !message.empty() && (message[0] == '\'' || std::isdigit((unsigned char)message[0]) ||
                                                      message[0] == '-');
    return label + (startsWithValue ? " " : ": ") + message;
}

std::string scalarText(const json& v) {
    if (v.is_string()) return v.get<std::string>();
    if (v.is_number() || v.is_boolean()) return v.dump();
    throw Error("must be a string, number or boolean");
}

}  // namespace

const std::vector<RenderOption>& renderOptions() {
    static const std::vector<RenderOption> table = makeTable();
    return table;
}

std::string RenderOption::label(RenderOptionPlace place) const { return place == kInScene ? "render." + spec.name : spec.name; }

const RenderOption* findRenderOption(std::string_view key, RenderOptionPlace place) {
    for (const RenderOption& o : renderOptions()) {
        if (!(o.places & place)) continue;
        if (o.spec.name == key) return &o;
        for (const std::string& a : o.aliases)
            if (a == key) return &o;
    }
    return nullptr;
}

std::string renderOptionNames(RenderOptionPlace place) {
    std::string names;
    for (const RenderOption& o : renderOptions())
        if (o.places & place) names += (names.empty() ? "" : ", ") + o.spec.name;
    return names;
}

namespace {

std::string checkedText(const RenderOption& option, const std::string& text, const std::string& label) {
    try {
        return checked(option.spec, text);
    } catch (const Error& e) {
        throw Error(labelled(label, e.what()));
    }
}

}  // namespace

void applyRenderOption(RenderRequest& r, const RenderOption& option, const std::string& text, const std::string& label) {
    const std::string canonical = checkedText(option, text, label);
    if (option.storeInScene) option.storeInScene(r, canonical);
    else option.store(r, canonical);
}

void applyRenderOption(SceneRender& r, const RenderOption& option, const std::string& text, const std::string& label) {
    if (!option.storeInScene) throw Error(label + " is not a scene setting");  // the table's places say where it may go
    option.storeInScene(r, checkedText(option, text, label));
}

std::vector<std::string> renderOptionTexts(const RenderOption& option, const json& value) {
    if (option.repeated) {
        std::vector<std::string> out;
        if (value.is_object()) {
            for (const auto& item : value.items()) {
                try {
                    out.push_back(item.key() + "=" + scalarText(item.value()));
                } catch (const Error& e) {
                    throw Error("'" + item.key() + "' " + e.what());
                }
            }
            return out;
        }
        if (value.is_array()) {
            for (const json& v : value) {
                if (!v.is_string()) throw Error("must be an object of key: value or an array of \"key=value\"");
                out.push_back(v.get<std::string>());
            }
            return out;
        }
        throw Error("must be an object of key: value");
    }
    if (option.spec.name == "resolution" && value.is_array()) {
        if (value.size() != 2 || !value[0].is_number_integer() || !value[1].is_number_integer())
            throw Error("must be [width, height] (integers) or \"WxH\"");
        return {std::to_string(value[0].get<long long>()) + "x" + std::to_string(value[1].get<long long>())};
    }
    return {scalarText(value)};
}

namespace {

// Each key of `object` through the table: its texts checked and handed to `apply`.
void readOptions(const json& object, RenderOptionPlace place, const RenderOptionFailure& fail,
                 const std::function<void(const RenderOption&, const std::string&, const std::string&)>& apply) {
    for (const auto& item : object.items()) {
        const std::string& key = item.key();
        const RenderOption* o = findRenderOption(key, place);
        if (!o && place == kInScene && findRenderOption(key, kOnCommandLine))
            fail(key, "render." + key + " belongs to the command line or a batch job, not to a scene (scene keys: " +
                          renderOptionNames(kInScene) + ")");
        if (!o && place == kInScene) fail(key, "unknown key '" + key + "' in render; valid keys: " + renderOptionNames(place));
        if (!o) fail(key, "unknown key '" + key + "' (valid: " + renderOptionNames(place) + ")");
        std::vector<std::string> texts;
        try {
            texts = renderOptionTexts(*o, item.value());
        } catch (const Error& e) {
            fail(key, o->label(place) + " " + e.what());
        }
        for (const std::string& t : texts) {
            try {
                apply(*o, t, o->label(place));
            } catch (const Error& e) {
                fail(key, e.what());
            }
        }
    }
}

}  // namespace

void readRenderOptions(RenderRequest& r, const json& job, const RenderOptionFailure& fail) {
    readOptions(job, kInBatchJob, fail, [&](const RenderOption& o, const std::string& text, const std::string& label) {
        applyRenderOption(r, o, text, label);
    });
}

void readSceneRender(SceneRender& r, const json& block, const RenderOptionFailure& fail) {
    readOptions(block, kInScene, fail, [&](const RenderOption& o, const std::string& text, const std::string& label) {
        applyRenderOption(r, o, text, label);
    });
}

std::string defaultTechnique(const std::vector<std::string>& sets) {
    for (const std::string& kv : sets)
        if (kv == "compat=vdb_render") return "volume.singlescatter";
    return "volume.raymarch";
}

namespace {

// The table's defaults of the scene options that have one.
const SceneRender& tableDefaults() {
    static const SceneRender defaults = [] {
        SceneRender d;
        for (const RenderOption& o : renderOptions())
            if (o.storeInScene && !o.repeated && !o.spec.defaultValue.empty()) o.storeInScene(d, o.spec.defaultValue);
        return d;
    }();
    return defaults;
}

template <typename T>
T firstGiven(const std::optional<T>& given, const std::optional<T>& scene, const std::optional<T>& fallback) {
    return given ? *given : scene ? *scene : *fallback;
}

}  // namespace

EffectiveRender effectiveRender(const SceneRender& given, const SceneRender& scene) {
    EffectiveRender e;
    e.sets = scene.sets;
    e.sets.insert(e.sets.end(), given.sets.begin(), given.sets.end());
    const SceneRender& defaults = tableDefaults();
    e.technique = firstGiven(given.technique, scene.technique, std::optional(defaultTechnique(e.sets)));
    e.resolution = firstGiven(given.resolution, scene.resolution, defaults.resolution);
    e.spp = firstGiven(given.spp, scene.spp, defaults.spp);
    e.seed = firstGiven(given.seed, scene.seed, defaults.seed);
    return e;
}

}  // namespace weft
