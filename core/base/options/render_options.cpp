#include "core/base/options/render_options.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/base/error.hpp"
#include "core/base/options/frames.hpp"
#include "core/base/options/exr_options.hpp"
#include "core/base/options/param_value.hpp"

namespace weft {

namespace {

using nlohmann::json;

constexpr unsigned kEverywhere = kOnCommandLine | kInBatchJob | kInScene;

bool resolutionOf(const std::string& text, int& w, int& h) {
    char x = 0, extra = 0;
    return std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) == 3 && (x == 'x' || x == 'X') && w >= 1 &&
           h >= 1 && w <= 65536 && h <= 65536;
}

// Checks for string options: each throws a message that starts with the value.
void checkResolution(const std::string& t) {
    int w = 0, h = 0;
    if (!resolutionOf(t, w, h)) throw Error("'" + t + "': expected WxH with W and H in [1, 65536], e.g. 512x512");
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

RenderOption option(ParamSpec spec, std::string cli, unsigned places, void (*store)(RenderRequest&, const std::string&),
                    std::vector<std::string> aliases = {}) {
    RenderOption o;
    o.spec = std::move(spec), o.cli = std::move(cli), o.places = places, o.store = store, o.aliases = std::move(aliases);
    return o;
}

std::vector<RenderOption> makeTable() {
    std::vector<RenderOption> t;
    t.push_back(option(stringParam("input", "", "scene .json, .vdb, .obj/.ply file, or builtin:NAME; # or @ = frame number"),
                       "input", kOnCommandLine | kInBatchJob, [](RenderRequest& r, const std::string& v) { r.input = v; }));
    t.push_back(option(stringParam("output", "", "output EXR (RGBA + AOVs + metadata); # or @ = frame number"), "-o,--output",
                       kOnCommandLine | kInBatchJob, [](RenderRequest& r, const std::string& v) { r.output = v; }));
    t.push_back(option(stringParam("preview", "", "also write a display-referred PNG/JPEG through OpenColorIO"), "--preview",
                       kOnCommandLine | kInBatchJob, [](RenderRequest& r, const std::string& v) { r.preview = v; }));
    t.push_back(option(stringParam("stats", "", "write counters, timings and parameters as JSON"), "--stats",
                       kOnCommandLine | kInBatchJob, [](RenderRequest& r, const std::string& v) { r.stats = v; }));
    t.push_back(option(stringParam("frames", "", "frames to render, e.g. 1001-1100x2, 1,3,5-9, -5--1 (names need # or @)", checkFrames),
                       "--frames", kOnCommandLine | kInBatchJob, [](RenderRequest& r, const std::string& v) { r.frames = v; }));
    t.push_back(option(stringParam("tile", "", "render only tile i of n (1-based row bands), e.g. 2/4; merge with `weft merge`", checkTile),
                       "--tile", kOnCommandLine | kInBatchJob, [](RenderRequest& r, const std::string& v) { r.tile = v; }));
    t.push_back(option(stringParam("grid", "", "grid of a bare .vdb (default: density, else the first float grid)"), "--grid",
                       kOnCommandLine | kInBatchJob, [](RenderRequest& r, const std::string& v) { r.grid = v; }));
    t.push_back(option(stringParam("technique", "volume.raymarch",
                                   "technique (weft help lists them); volume.singlescatter with set compat=vdb_render"),
                       "--technique", kEverywhere, [](RenderRequest& r, const std::string& v) { r.technique = v; }));
    t.push_back(option(stringParam("set", "", "technique parameter key=value, repeatable (weft help TECHNIQUE)", checkKeyValue),
                       "--set", kEverywhere, [](RenderRequest& r, const std::string& v) { r.sets.push_back(v); }, {"params"}));
    t.back().repeated = true;
    t.push_back(option(stringParam("resolution", "512x512", "image size WxH ([W, H] in JSON)", checkResolution), "--res,--resolution",
                       kEverywhere, [](RenderRequest& r, const std::string& v) { r.resolution = v; }, {"res"}));
    t.push_back(option(intParam("spp", 1, 1, 1 << 20, "camera samples per pixel"), "--spp", kEverywhere,
                       [](RenderRequest& r, const std::string& v) { r.spp = int(std::stoll(v)); }));
    t.push_back(option(intParam("seed", 0, 0, std::int64_t(1) << 53, "random seed (same seed, same image)"), "--seed", kEverywhere,
                       [](RenderRequest& r, const std::string& v) { r.seed = std::uint64_t(std::stoull(v)); }));
    t.push_back(option(intParam("threads", 0, 0, 4096, "worker threads, 0 = all cores (the image does not depend on it)"), "--threads",
                       kOnCommandLine | kInBatchJob, [](RenderRequest& r, const std::string& v) { r.threads = int(std::stoll(v)); }));
    t.push_back(option(floatParam("max-memory", 0, 0, 1e6, "refuse renders estimated to need more GiB than this: the technique's buffers per pixel and the scene (0 = 3/4 of physical memory)"),
                       "--max-memory", kOnCommandLine | kInBatchJob,
                       [](RenderRequest& r, const std::string& v) { r.maxMemoryGiB = std::stod(v); }));
    t.push_back(option(enumParam("compression", kDefaultExrCompression, exrCompressionNames(),
                                 "EXR compression; lossless: none, rle, zips, zip, piz; lossy: pxr24 (floats rounded to 24 bits), "
                                 "b44, b44a (lossy on half channels), dwaa, dwab (lossy on R, G, B, Y, and on a layer's .R/.G/.B/.Y such as N.Y)"),
                       "--compression", kOnCommandLine | kInBatchJob,
                       [](RenderRequest& r, const std::string& v) { r.compression = v; }));
    t.push_back(option(stringParam("pixel_type", "float",
                                   "EXR pixel type, repeatable, later ones win: half or float for every channel, or CHANNEL=TYPE "
                                   "for a channel, a layer (N: N.X, N.Y, N.Z) or aovs (all but R, G, B, A); half saturates at 65504",
                                   checkPixelTypeSpec),
                       "-d,--pixel-type", kOnCommandLine | kInBatchJob,
                       [](RenderRequest& r, const std::string& v) { r.pixelTypes.push_back(v); }));
    t.back().repeated = true;
    t.push_back(option(boolParam("verbose", false, "print the counter table and timings"), "-v,--verbose", kOnCommandLine | kInBatchJob,
                       [](RenderRequest& r, const std::string& v) { r.verbose = v == "true"; }));
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

std::string RenderOption::label(RenderOptionPlace place) const {
    if (place == kInScene) return "render." + spec.name;
    if (place == kInBatchJob) return spec.name;
    const auto dashes = cli.find("--");
    if (dashes == std::string::npos) return cli;  // positional
    return cli.substr(dashes, cli.find(',', dashes) - dashes);
}

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

void applyRenderOption(RenderRequest& r, const RenderOption& option, const std::string& text, const std::string& label) {
    std::string canonical;
    try {
        canonical = checked(option.spec, text);
    } catch (const Error& e) {
        throw Error(labelled(label, e.what()));
    }
    option.store(r, canonical);
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

void readRenderOptions(RenderRequest& r, const json& object, RenderOptionPlace place,
                       const std::function<void(const std::string&, const std::string&)>& fail) {
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
                applyRenderOption(r, *o, t, o->label(place));
            } catch (const Error& e) {
                fail(key, e.what());
            }
        }
    }
}

std::string defaultTechnique(const std::vector<std::string>& sets) {
    for (const std::string& kv : sets)
        if (kv == "compat=vdb_render") return "volume.singlescatter";
    return "volume.raymarch";
}

RenderRequest effectiveRequest(const RenderRequest& given, const RenderRequest& scene) {
    RenderRequest q = given;
    q.sets = scene.sets;
    q.sets.insert(q.sets.end(), given.sets.begin(), given.sets.end());
    if (!q.technique) q.technique = scene.technique;
    if (!q.technique) q.technique = defaultTechnique(q.sets);
    const auto fallback = [&](auto& field, const auto& sceneValue, const char* name) {
        if (!field) field = sceneValue;
        if (!field) findRenderOption(name, kInScene)->store(q, findRenderOption(name, kInScene)->spec.defaultValue);
    };
    fallback(q.resolution, scene.resolution, "resolution");
    fallback(q.spp, scene.spp, "spp");
    fallback(q.seed, scene.seed, "seed");
    return q;
}

void checkRenderNumber(std::string_view name, double value, RenderOptionPlace place) {
    const RenderOption* o = findRenderOption(name, place);
    if (o && !(value >= o->spec.min && value <= o->spec.max))
        throw Error(o->label(place) + " " + formatNumber(value) + " is outside " + o->spec.allowedText());
}

std::pair<int, int> parseResolution(const std::string& text) {
    int w = 0, h = 0;
    if (!resolutionOf(text, w, h))
        throw Error("bad resolution '" + text + "': expected WxH with W and H in [1, 65536], e.g. 512x512");
    return {w, h};
}

namespace {

std::string places(const RenderOption& o) {
    std::string s;
    if (o.places & kOnCommandLine) s += o.label(kOnCommandLine);
    if (o.places & kInBatchJob) s += std::string(s.empty() ? "" : ", ") + "batch";
    if (o.places & kInScene) s += std::string(s.empty() ? "" : ", ") + "scene";
    return s;
}

std::string jsonNames(const RenderOption& o) {
    std::string s = o.spec.name;
    for (const std::string& a : o.aliases) s += " (or " + a + ")";
    return s;
}

}  // namespace

std::string renderOptionsHelp() {
    std::string out;
    char line[512];
    for (const RenderOption& o : renderOptions()) {
        std::snprintf(line, sizeof line, "  %-26s %-6s %-9s %-20s %s\n    given as: %s\n", jsonNames(o).c_str(),
                      paramTypeName(o.spec.type), o.spec.defaultValue.empty() ? "-" : o.spec.defaultValue.c_str(),
                      o.spec.type == ParamType::String ? "" : o.spec.allowedText().c_str(), o.spec.doc.c_str(), places(o).c_str());
        out += line;
    }
    return out;
}

std::string renderOptionsMarkdown() {
    std::string out =
        "| key (batch, scene) | command line | batch | scene | type | default | allowed | meaning |\n"
        "|---|---|---|---|---|---|---|---|\n";
    for (const RenderOption& o : renderOptions()) {
        std::string doc = o.spec.doc;
        for (std::size_t p = doc.find('|'); p != std::string::npos; p = doc.find('|', p + 2)) doc.replace(p, 1, "\\|");
        out += "| `" + o.spec.name + "`";
        for (const std::string& a : o.aliases) out += " or `" + a + "`";
        out += " | `" + o.cli + "` | " + ((o.places & kInBatchJob) ? "yes" : "no") + " | " + ((o.places & kInScene) ? "yes" : "no") +
               " | " + paramTypeName(o.spec.type) + " | " + (o.spec.defaultValue.empty() ? "" : "`" + o.spec.defaultValue + "`") +
               " | " + (o.spec.type == ParamType::String ? "" : o.spec.allowedMarkdown()) + " | " + doc + " |\n";
    }
    return out;
}

}  // namespace weft
