// Scene files: strict JSON. Every object lists the keys it accepts; an unknown
// key, a wrong type or a value out of range is an error at file:line:column.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>

#include "core/sampling/analytic2d.hpp"
#include "core/base/error.hpp"
#include "core/base/files/input_file.hpp"
#include "core/base/options/frames.hpp"
#include "core/base/files/json_doc.hpp"
#include "core/base/options/params.hpp"
#include "core/base/options/render_options.hpp"
#include "core/scene/placement.hpp"
#include "core/scene/scene_budget.hpp"
#include "core/scene/world_range.hpp"
#include "core/scene/scene.hpp"
#include "core/volume/volume_grids.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace weft {

namespace {

// Typed, position-aware access to one JSON object of the scene.
class ObjectReader {
public:
    ObjectReader(const JsonDoc& doc, std::string pointer, std::string what, std::set<std::string> keys)
        : doc_(doc), pointer_(std::move(pointer)), what_(std::move(what)) {
        const json& node = value();
        if (!node.is_object()) failAt(pointer_, what_ + " must be an object");
        for (const auto& item : node.items())
            if (!keys.count(item.key())) {
                std::string valid;
                for (const auto& k : keys) valid += (valid.empty() ? "" : ", ") + k;
                failAt(pointer_ + "/" + item.key() + "#key", "unknown key '" + item.key() + "' in " + what_ + "; valid keys: " + valid);
            }
    }
    const json& value() const { return doc_.root().at(json::json_pointer(pointer_)); }
    bool has(const std::string& key) const { return value().contains(key); }
    std::string child(const std::string& key) const { return pointer_ + "/" + key; }

    [[noreturn]] void failAt(const std::string& pointer, const std::string& msg) const {
        throw Error(doc_.where(pointer) + ": " + msg);
    }
    [[noreturn]] void fail(const std::string& key, const std::string& msg) const { failAt(child(key), msg); }

    double number(const std::string& key, double def, double lo, double hi) const {
        if (!has(key)) return def;
        const json& v = value()[key];
        if (!v.is_number()) fail(key, what_ + "." + key + " must be a number");
        const double d = v.get<double>();
        if (!(d >= lo && d <= hi))
            fail(key, what_ + "." + key + " = " + v.dump() + " is outside [" + formatNumber(lo) + ", " + formatNumber(hi) + "]");
        return d;
    }
    std::string string(const std::string& key, const std::string& def) const {
        if (!has(key)) return def;
        const json& v = value()[key];
        if (!v.is_string()) fail(key, what_ + "." + key + " must be a string");
        return v.get<std::string>();
    }
    Vec3d vec3(const std::string& key, const Vec3d& def) const {
        if (!has(key)) return def;
        const json& v = value()[key];
        if (!v.is_array() || v.size() != 3) fail(key, what_ + "." + key + " must be an array of 3 numbers");
        Vec3d out;
        for (int i = 0; i < 3; ++i) {
            if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) fail(key, what_ + "." + key + " must be an array of 3 finite numbers");
            out[i] = v[i].get<double>();
        }
        return out;
    }
    const JsonDoc& doc() const { return doc_; }
    const std::string& pointer() const { return pointer_; }

private:
    const JsonDoc& doc_;
    std::string pointer_;
    std::string what_;
};

constexpr double kHuge = 1e30;

Camera readCamera(const ObjectReader& r, const Camera& defaults = Camera{}) {
    Camera cam;
    cam.eye = r.vec3("eye", defaults.eye);
    cam.target = r.vec3("target", defaults.target);
    cam.up = r.vec3("up", defaults.up);
    cam.fovY = r.number("fov", defaults.fovY, 0.01, 179.0);
    if ((cam.target - cam.eye).length() < 1e-12) r.fail("target", "camera.target must differ from camera.eye");
    if ((cam.target - cam.eye).cross(cam.up).length() < 1e-12 * (cam.target - cam.eye).length())
        r.fail("up", "camera.up must not be parallel to the view direction");
    return cam;
}

// "camera": {"up": ..., "fov": ..., "keys": [{"frame": F, "eye": ..., "target": ...}, ...]}:
// a CameraPath; values a key leaves out come from the camera object.
CameraPath readCameraPath(const ObjectReader& r) {
    const Camera base = readCamera(r);
    const json& keys = r.value()["keys"];
    if (!keys.is_array() || keys.empty()) r.fail("keys", "camera.keys must be a non-empty array of keys");
    CameraPath path;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        ObjectReader k(r.doc(), r.child("keys/" + std::to_string(i)), "camera key", {"frame", "eye", "target", "up", "fov"});
        if (!k.has("frame")) k.failAt(k.pointer(), "a camera key needs a 'frame'");
        const double f = k.number("frame", 0, -1e9, 1e9);
        if (!path.keys.empty() && f <= path.keys.back().first) k.fail("frame", "camera key frames must increase");
        path.keys.emplace_back(f, readCamera(k, base));
    }
    return path;
}

// "shutter": [open, close] in frames relative to the frame, open <= close.
Shutter readShutter(const ObjectReader& r) {
    const json& v = r.value()["shutter"];
    const auto finite = [](const json& x) { return x.is_number() && std::abs(x.get<double>()) <= 100.0; };
    if (!v.is_array() || v.size() != 2 || !finite(v[0]) || !finite(v[1]) || v[0].get<double>() > v[1].get<double>())
        r.fail("shutter", "camera.shutter must be [open, close] in frames relative to the frame, open <= close, within +-100");
    return {v[0].get<double>(), v[1].get<double>()};
}

void readSceneCamera(const ObjectReader& cam, std::optional<int> frame, Scene& scene) {
    if (cam.has("shutter")) scene.shutter = readShutter(cam);
    if (!cam.has("keys")) {
        scene.camera = readCamera(cam);
        return;
    }
    scene.cameraPath = readCameraPath(cam);
    scene.frame = frame ? double(*frame) : scene.cameraPath.keys.front().first;
    scene.camera = scene.cameraPath.at(scene.frame);
}

TransferFunction readTransferFunction(const ObjectReader& r, const Volume& vol) {
    double lo = std::min(0.0f, vol.valueMin), hi = vol.valueMax > lo ? vol.valueMax : lo + 1.0;
    if (r.has("range")) {
        const json& v = r.value()["range"];
        if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number() || !(v[1].get<double>() > v[0].get<double>()))
            r.fail("range", "transfer_function.range must be [min, max] with max > min");
        lo = v[0].get<double>(), hi = v[1].get<double>();
    }
    if (!r.has("points")) return TransferFunction::defaultFor(lo, hi);
    const json& pts = r.value()["points"];
    if (!pts.is_array() || pts.empty()) r.fail("points", "transfer_function.points must be a non-empty array");
    std::vector<TfPoint> points;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        ObjectReader p(r.doc(), r.child("points") + "/" + std::to_string(i), "transfer_function point", {"s", "color", "extinction"});
        TfPoint tp;
        tp.s = p.number("s", 0.0, 0.0, 1.0);
        const Vec3d c = p.vec3("color", Vec3d(1, 1, 1));
        if (c.x() < 0 || c.y() < 0 || c.z() < 0) p.fail("color", "transfer_function colour must not be negative");
        tp.color = {c.x(), c.y(), c.z()};
        tp.extinction = p.number("extinction", 0.0, 0.0, kHuge);
        if (!points.empty() && tp.s < points.back().s) p.fail("s", "transfer_function points must be sorted by s");
        points.push_back(tp);
    }
    return TransferFunction(lo, hi, std::move(points));
}

// "scale" (a positive number or three), "rotate" (degrees), "translate".
Placement readPlacement(const ObjectReader& r) {
    Placement p;
    if (r.has("scale") && r.value()["scale"].is_number()) p.scale = Vec3d(r.number("scale", 1.0, 1e-12, kHuge));
    else p.scale = r.vec3("scale", p.scale);
    for (int i = 0; i < 3; ++i)
        if (!(p.scale[i] >= 1e-12 && p.scale[i] <= kHuge)) r.fail("scale", "scale must be positive (a number or [sx, sy, sz])");
    p.rotateDegrees = r.vec3("rotate", p.rotateDegrees);
    for (int i = 0; i < 3; ++i)
        if (std::abs(p.rotateDegrees[i]) > 3600) r.fail("rotate", "rotate must be [rx, ry, rz] in degrees, each within +-3600");
    p.translate = r.vec3("translate", p.translate);
    if (!withinWorld(p.translate)) r.fail("translate", "translate must lie within +-" + formatNumber(kWorldLimit) + " scene units on each axis");
    return p;
}

// "medium": {"absorb": [r, g, b], "scatter": [r, g, b], "g": anisotropy}.
VolumeMedium readMedium(const ObjectReader& r) {
    VolumeMedium m;
    m.fromScene = true;
    m.absorb = r.vec3("absorb", m.absorb);
    m.scatter = r.vec3("scatter", m.scatter);
    for (int i = 0; i < 3; ++i) {
        if (!(m.absorb[i] >= 0 && m.absorb[i] <= kHuge)) r.fail("absorb", "medium.absorb must be three numbers >= 0");
        if (!(m.scatter[i] >= 0 && m.scatter[i] <= kHuge)) r.fail("scatter", "medium.scatter must be three numbers >= 0");
    }
    m.g = r.number("g", 0.0, -0.99, 0.99);
    return m;
}

// A path of the scene: relative to its folder; "#" names the frame (volume files only).
fs::path scenePath(const std::string& text, const fs::path& baseDir, std::optional<int> frame) {
    fs::path file = frame ? expandFrameName(text, *frame) : text;
    return file.is_relative() ? baseDir / file : file;
}

// The keys "grids" accepts: the roles and their aliases ("albedo").
std::set<std::string> gridKeys() {
    std::set<std::string> keys(gridRoles().begin(), gridRoles().end());
    for (const auto& [alias, role] : gridRoleAliases()) keys.insert(alias);
    return keys;
}

// "grids": {"density": NAME, "temperature": NAME | {"file": F, "grid": NAME}, "emission": ..., "velocity": ..., "color": ...}.
std::map<std::string, GridSource> readGridSources(const ObjectReader& r, const fs::path& baseDir, std::optional<int> frame) {
    const ObjectReader g(r.doc(), r.child("grids"), "grids", gridKeys());
    std::map<std::string, GridSource> sources;
    for (const std::string& key : gridKeys()) {
        if (!g.has(key)) continue;
        const auto alias = gridRoleAliases().find(key);
        const std::string role = alias == gridRoleAliases().end() ? key : alias->second;
        if (sources.count(role)) g.fail(key, "grids." + key + " names the " + role + " grid again; give it once");
        const json& v = g.value()[key];
        if (v.is_string()) {
            sources[role].grid = v.get<std::string>();
            continue;
        }
        if (role == "density") g.fail(key, "grids.density must be a grid name of the volume's 'file'");
        if (!v.is_object()) g.fail(key, "grids." + key + " must be a grid name or {\"file\": ..., \"grid\": ...}");
        const ObjectReader o(r.doc(), g.child(key), "grids." + key, {"file", "grid"});
        if (!o.has("file")) o.failAt(o.pointer(), "grids." + key + " needs a 'file' (or give the grid's name alone)");
        sources[role] = {scenePath(o.string("file", ""), baseDir, frame).string(), o.string("grid", "")};
    }
    return sources;
}

// "emission": {"temperature_scale", "temperature_offset", "blackbody_intensity", "color", "strength"}.
EmissionSettings readEmission(const ObjectReader& r) {
    EmissionSettings e;
    e.temperatureScale = r.number("temperature_scale", e.temperatureScale, 0.0, 1e9);
    e.temperatureOffset = r.number("temperature_offset", e.temperatureOffset, -1e9, 1e9);
    e.blackbodyIntensity = r.number("blackbody_intensity", e.blackbodyIntensity, 0.0, 1e12);
    e.color = r.vec3("color", e.color);
    for (int i = 0; i < 3; ++i)
        if (!(e.color[i] >= 0 && e.color[i] <= kHuge)) r.fail("color", "emission.color must be three numbers >= 0");
    e.strength = r.number("strength", e.strength, 0.0, 1e12);
    return e;
}

// The temperature and emission grids of a volume whose density is read,
// in the density's index space, and Volume::grids saying what was read.
struct EmissionGrids {
    openvdb::FloatGrid::Ptr temperature, emission;
};

// Where a role's grid comes from: its own file, a grid (by name) of the
// volume's file, or nowhere.
std::optional<GridSource> roleSource(const std::string& role, const std::map<std::string, std::string>& names,
                                     const std::map<std::string, GridSource>& own, const std::string& volumeFile) {
    if (const auto it = own.find(role); it != own.end()) return it->second;
    if (const auto n = names.find(role); n != names.end()) return GridSource{volumeFile, n->second};
    return std::nullopt;
}

// Volume::grids notes what a role read ("temperature=heat", and the file when its own).
void noteGrid(Volume& vol, const std::string& role, const std::string& grid, const std::string& file, const std::string& volumeFile) {
    vol.grids += " " + role + "=" + grid + (file == volumeFile ? "" : " (" + file + ")");
}

EmissionGrids readEmissionGrids(Volume& vol, const std::map<std::string, std::string>& names, const std::map<std::string, GridSource>& own,
                                const std::string& volumeFile) {
    EmissionGrids out;
    for (const std::string role : {"temperature", "emission"}) {
        const std::optional<GridSource> src = roleSource(role, names, own, volumeFile);
        if (!src) continue;
        auto g = inIndexSpaceOf(readFloatGrid(src->file, src->grid, role), vol.grid->transform());
        noteGrid(vol, role, g->getName(), src->file, volumeFile);
        (role == std::string("temperature") ? out.temperature : out.emission) = g;
    }
    return out;
}

// The colour grid named for the volume (null when none) as tints in the
// density's index space, under the density's transform as read (the
// caller moves it with the density's placement).
openvdb::Vec3SGrid::Ptr readColorGrid(Volume& vol, const std::map<std::string, std::string>& names, const std::map<std::string, GridSource>& own,
                                      const std::string& volumeFile) {
    const std::optional<GridSource> src = roleSource("color", names, own, volumeFile);
    if (!src) return nullptr;
    const openvdb::GridBase::Ptr color = readFloatOrVec3Grid(src->file, src->grid, "color");
    noteGrid(vol, "color", color->getName(), src->file, volumeFile);
    return buildColorGrid(*color, vol.grid->transform());
}

// "motion": {"velocity_scale", "fps"}.
MotionSettings readMotion(const ObjectReader& r) {
    MotionSettings m;
    m.velocityScale = r.number("velocity_scale", m.velocityScale, -1e6, 1e6);
    m.fps = r.number("fps", m.fps, 1e-3, 1e6);
    return m;
}

// The velocity grid named for the volume (null when none), as motion in
// the density's index space, and Volume::grids saying what was read.
void readMotionGrid(Volume& vol, const std::map<std::string, std::string>& names, const std::map<std::string, GridSource>& own,
                    const MotionSettings& settings) {
    const std::optional<GridSource> src = roleSource("velocity", names, own, vol.source);
    if (!src) return;
    const auto velocity = readVec3Grid(src->file, src->grid, "velocity");
    noteGrid(vol, "velocity", velocity->getName(), src->file, vol.source);
    vol.motion = buildMotionGrid(velocity, vol.grid->transform(), settings, vol.maxMotion);
}

void buildEmission(Volume& vol, const EmissionGrids& grids, const EmissionSettings& settings) {
    if (!grids.temperature && !grids.emission) return;
    vol.emission = buildEmissionGrid(grids.temperature.get(), grids.emission.get(), settings, vol.grid->transform());
}

const std::set<std::string> kVolumeKeys{"file", "grid", "grids", "emission", "motion", "procedural", "resolution", "seed",
                                        "transfer_function", "medium", "translate", "rotate", "scale"};

// A volume's settings that need none of its grids, checked before any volume loads.
void checkVolumeSettings(const ObjectReader& r) {
    if (r.has("file") == r.has("procedural")) r.failAt(r.pointer(), "a volume needs exactly one of 'file' or 'procedural'");
    r.number("resolution", 128, 4, 1024);
    r.number("seed", 1, 0, 4294967295.0);
    readPlacement(r);
    if (r.has("medium")) readMedium(ObjectReader(r.doc(), r.child("medium"), "medium", {"absorb", "scatter", "g"}));
    if (r.has("motion")) readMotion(ObjectReader(r.doc(), r.child("motion"), "motion", {"velocity_scale", "fps"}));
    if (r.has("emission"))
        readEmission(ObjectReader(r.doc(), r.child("emission"), "emission",
                                  {"temperature_scale", "temperature_offset", "blackbody_intensity", "color", "strength"}));
}

// Grids read by this scene so far, by file and grid name: a file named by
// many volumes is read once and its tree shared (1,000 references to one
// small .vdb took 6.2 GB).
using LoadedGrids = std::map<std::pair<std::string, std::string>, openvdb::FloatGrid::ConstPtr>;

openvdb::FloatGrid::ConstPtr readSharedFloatGrid(const std::string& path, const std::string& grid, LoadedGrids& loaded) {
    std::error_code ec;
    const std::pair<std::string, std::string> key{fs::weakly_canonical(path, ec).string(), grid};
    if (const auto it = loaded.find(key); it != loaded.end()) return it->second;
    openvdb::FloatGrid::ConstPtr read = readFloatGrid(path, grid);
    loaded.emplace(key, read);
    return read;
}

Volume readVolume(const ObjectReader& r, const fs::path& baseDir, std::optional<int> frame, LoadedGrids& loaded) {
    Volume vol;
    const bool fromFile = r.has("file"), procedural = r.has("procedural");
    if (fromFile == procedural) r.failAt(r.pointer(), "a volume needs exactly one of 'file' or 'procedural'");
    // Values are read first so their own errors keep their own positions.
    // A frame-numbered file ("smoke.#.vdb") names the frame being rendered.
    const fs::path file = scenePath(r.string("file", ""), baseDir, frame);
    const std::string kind = r.string("procedural", "");
    const int res = int(r.number("resolution", 128, 4, 1024));
    const auto seed = std::uint64_t(r.number("seed", 1, 0, 4294967295.0));
    const std::map<std::string, GridSource> sources = r.has("grids") ? readGridSources(r, baseDir, frame) : std::map<std::string, GridSource>{};
    if (r.has("grid") && sources.count("density")) r.fail("grid", "name the density grid once: 'grid' or 'grids.density'");
    const std::string grid = sources.count("density") ? sources.at("density").grid : r.string("grid", "");
    std::map<std::string, std::string> names;
    std::map<std::string, GridSource> own;
    for (const auto& [role, src] : sources) {
        if (role == "density") continue;
        if (src.file.empty()) names[role] = src.grid;
        else own[role] = src;
    }
    if (procedural && !names.empty())
        r.fail("grids", "a procedural volume's grids need their own 'file'");
    const EmissionSettings settings =
        r.has("emission") ? readEmission(ObjectReader(r.doc(), r.child("emission"), "emission",
                                                      {"temperature_scale", "temperature_offset", "blackbody_intensity", "color", "strength"}))
                          : EmissionSettings{};
    const MotionSettings motion =
        r.has("motion") ? readMotion(ObjectReader(r.doc(), r.child("motion"), "motion", {"velocity_scale", "fps"})) : MotionSettings{};
    EmissionGrids emitting;
    openvdb::Vec3SGrid::Ptr color;
    try {
        vol.source = fromFile ? file.string() : "procedural:" + kind;
        vol.grid = fromFile ? readSharedFloatGrid(vol.source, grid, loaded) : makeProceduralGrid(kind, res, seed);
        vol.grids = "density=" + vol.grid->getName();
        emitting = readEmissionGrids(vol, names, own, vol.source);
        if (procedural && kind == "fire" && !emitting.temperature) {
            emitting.temperature = makeProceduralTemperature(res, seed);
            vol.grids += " temperature=" + emitting.temperature->getName();
        }
        readMotionGrid(vol, names, own, motion);  // before placement: velocities are in the file's world space
        color = readColorGrid(vol, names, own, vol.source);
    } catch (const Error& e) {
        r.fail(fromFile ? "file" : "procedural", e.what());
    }
    if (r.has("emission") && !emitting.temperature && !emitting.emission)
        r.fail("emission", "emission settings need a temperature or emission grid (see 'grids')");
    if (r.has("motion") && !vol.motion) r.fail("motion", "motion settings need a velocity grid (see 'grids')");
    vol.name = vol.grid->getName();
    const Placement placement = readPlacement(r);
    if (!placement.identity()) {
        try {
            vol.grid = placeGrid(vol.grid, placement.matrix());
        } catch (const openvdb::Exception&) {  // ArithmeticError: OpenVDB's words
            r.fail("scale", "the placement makes the volume's transform singular (is the scale too small?)");
        }
    }
    if (color) color->setTransform(vol.grid->transform().copy());  // its index space is the density's
    vol.color = color;
    try {
        buildEmission(vol, emitting, settings);
    } catch (const Error& e) {
        r.fail(r.has("emission") ? "emission" : "grids", e.what());
    }
    if (r.has("medium")) vol.medium = readMedium(ObjectReader(r.doc(), r.child("medium"), "medium", {"absorb", "scatter", "g"}));
    computeStatistics(vol);
    if (r.has("transfer_function")) {
        ObjectReader tf(r.doc(), r.child("transfer_function"), "transfer_function", {"range", "points"});
        vol.tf = readTransferFunction(tf, vol);
    } else {
        vol.tf = TransferFunction::defaultFor(vol.valueMin, vol.valueMax);
    }
    return vol;
}

void readMesh(const ObjectReader& r, const fs::path& baseDir, Scene& scene) {
    if (!r.has("file")) r.failAt(r.pointer(), "a mesh needs a 'file' (.obj or .ply)");
    const fs::path file = scenePath(r.string("file", ""), baseDir, std::nullopt);
    const int level = int(r.number("subdivision", 0, 0, 8));
    if (r.has("subdivision") && !r.value()["subdivision"].is_number_integer()) r.fail("subdivision", "mesh.subdivision must be an integer level in [0, 8]");
    const Placement placement = readPlacement(r);
    try {
        PolyMesh poly = readPolyMesh(file.string());
        transformMesh(poly, placement.matrix());
        // Embree needs finite coordinates; a huge scale can overflow floats.
        for (const Vec3f& v : poly.positions)
            if (!withinWorld(Vec3d(v.x(), v.y(), v.z())))
                r.fail("scale", "the placed mesh has a vertex beyond +-" + formatNumber(kWorldLimit) +
                                    " scene units, the range weft renders in (is a vertex, the scale or translate too large?)");
        scene.addMesh(subdivide(poly, level, file.string()));
    } catch (const Error& e) {
        r.fail("file", e.what());
    }
}

Light readLight(const ObjectReader& r) {
    Light light;
    const std::string type = r.string("type", "directional");
    if (type == "directional") light.type = LightType::Directional;
    else if (type == "point") light.type = LightType::Point;
    else if (type == "environment") light.type = LightType::Environment;
    else r.fail("type", "unknown light type '" + type + "' (known: directional|point|environment)");
    light.direction = r.vec3("direction", light.direction);
    if (light.type == LightType::Directional && light.direction.length() < 1e-12) r.fail("direction", "light direction must not be zero");
    light.direction = light.direction.unitSafe();
    light.position = r.vec3("position", light.position);
    const Vec3d c = r.vec3("color", Vec3d(1, 1, 1));
    light.color = Vec3f(float(c.x()), float(c.y()), float(c.z()));
    light.intensity = r.number("intensity", 1.0, 0.0, kHuge);
    return light;
}

std::set<std::string> keysOf(const json& object) {
    std::set<std::string> keys;
    if (object.is_object())
        for (const auto& item : object.items()) keys.insert(item.key());
    return keys;
}

// The render block goes through the same table as the command line and batch
// jobs; errors point at the key's position.
void readRender(const ObjectReader& r, SceneRender& out) {
    readSceneRender(out, r.value(), [&](const std::string& key, const std::string& msg) {
        r.fail(key, msg);
    });
}

template <class Fn>
void forEachInArray(const JsonDoc& doc, const std::string& pointer, const std::string& what, Fn fn) {
    const json& arr = doc.root().at(json::json_pointer(pointer));
    if (!arr.is_array()) throw Error(doc.where(pointer) + ": '" + what + "' must be an array");
    for (std::size_t i = 0; i < arr.size(); ++i) fn(pointer + "/" + std::to_string(i));
}

// Velocity blur needs an open shutter: a closed one drops the volumes'
// motion, an open one pads each moving volume's box by its reach.
void settleMotion(Scene& scene) {
    for (Volume& v : scene.volumes) {
        if (!v.motion) continue;
        if (scene.shutter.instant() || !(v.maxMotion > 0)) {
            v.motion.reset();
            continue;
        }
        v.motionReach = motionReachOf(v.maxMotion, scene.shutter.open, scene.shutter.close);
        if (!v.activeBox.empty()) v.activeBox.expand(int(std::ceil(v.motionReach)));
    }
}

Scene loadJsonScene(const std::string& path, std::optional<double> aspect, std::optional<int> frame, double limitBytes) {
    const JsonDoc doc = JsonDoc::load(path);
    ObjectReader top(doc, "", "scene", {"camera", "volumes", "meshes", "lights", "render"});
    const fs::path baseDir = fs::path(path).parent_path();
    Scene scene;
    scene.source = path;
    // What needs no file is read first, and every volume's and mesh's own
    // keys are checked, so a mistake anywhere in the document is found
    // before any grid or mesh loads (a bad camera.up once waited on 5 s of fire).
    if (top.has("render")) readRender(ObjectReader(doc, "/render", "render", keysOf(doc.root().at("render"))), scene.render);
    if (top.has("camera"))
        readSceneCamera(ObjectReader(doc, "/camera", "camera", {"eye", "target", "up", "fov", "keys", "shutter"}), frame, scene);
    if (top.has("lights"))
        forEachInArray(doc, "/lights", "lights", [&](const std::string& p) {
            scene.lights.push_back(readLight(ObjectReader(doc, p, "light", {"type", "direction", "position", "color", "intensity"})));
        });
    const auto volumeAt = [&](const std::string& p) { return ObjectReader(doc, p, "volume", kVolumeKeys); };
    const auto meshAt = [&](const std::string& p) { return ObjectReader(doc, p, "mesh", {"file", "subdivision", "scale", "rotate", "translate"}); };
    if (top.has("volumes")) forEachInArray(doc, "/volumes", "volumes", [&](const std::string& p) { checkVolumeSettings(volumeAt(p)); });
    if (top.has("meshes")) forEachInArray(doc, "/meshes", "meshes", [&](const std::string& p) { readPlacement(meshAt(p)); });
    requireLoadWithin(sceneFileLoadBytes(doc.root(), [&](const std::string& f) { return scenePath(f, baseDir, frame).string(); },
                                         [&](const std::string& f) { return scenePath(f, baseDir, std::nullopt).string(); }),
                      limitBytes, "scene '" + path + "'");
    LoadedGrids loaded;
    if (top.has("volumes"))
        forEachInArray(doc, "/volumes", "volumes", [&](const std::string& p) { scene.volumes.push_back(readVolume(volumeAt(p), baseDir, frame, loaded)); });
    if (top.has("meshes")) forEachInArray(doc, "/meshes", "meshes", [&](const std::string& p) { readMesh(meshAt(p), baseDir, scene); });
    if (!top.has("camera") && (!scene.volumes.empty() || !scene.meshes.empty())) {
        double sceneAspect = 1.0;
        if (const auto& res = scene.render.resolution) sceneAspect = double(res->width) / res->height;
        scene.camera = Camera::framing(scene.worldBox(), 40.0, aspect.value_or(sceneAspect));
    }
    settleMotion(scene);
    return scene;
}

Scene sceneAroundVolume(Volume vol, const std::string& source, double aspect) {
    Scene scene;
    scene.source = source;
    scene.volumes.push_back(std::move(vol));
    scene.camera = Camera::framing(scene.worldBox(), 40.0, aspect);
    return scene;
}

// Density, temperature and emission by their conventional names
// (core/volume/volume_grids.hpp), at the default emission settings.
Scene loadBareVdb(const std::string& path, double aspect, const std::string& gridName, double limitBytes) {
    Volume vol;
    vol.source = path;
    requireRegularFile(path, "volume");
    requireLoadWithin(vdbLoadBytes(path), limitBytes, "volume '" + path + "'");
    std::map<std::string, std::string> names = pickConventionalGrids(path, gridName);
    names.erase("velocity");  // a bare .vdb's shutter is closed: nothing to blur
    vol.grid = readFloatGrid(path, names.at("density"));
    vol.name = vol.grid->getName();
    vol.grids = "density=" + vol.name;
    buildEmission(vol, readEmissionGrids(vol, names, {}, path), EmissionSettings{});
    vol.color = readColorGrid(vol, names, {}, path);
    vol.gridsPicked = names.size() > 1;
    computeStatistics(vol);
    vol.tf = TransferFunction::defaultFor(vol.valueMin, vol.valueMax);
    return sceneAroundVolume(std::move(vol), path, aspect);
}

// The analytic 2D images need no volume: the scene only names the technique.
Scene loadAnalyticBuiltin(const std::string& name) {
    Scene scene;
    scene.source = "builtin:" + name;
    scene.render.technique = "analytic.2d";
    scene.render.sets.push_back("scene=" + name);
    return scene;
}

Scene loadBareMesh(const std::string& path, double aspect, double limitBytes) {
    Scene scene;
    scene.source = path;
    requireLoadWithin(meshLoadBytes(path), limitBytes, "mesh '" + path + "'");
    scene.addMesh(triangulate(readPolyMesh(path), path));
    scene.camera = Camera::framing(scene.worldBox(), 40.0, aspect);
    scene.render.technique = "mesh.pathtrace";
    bool emits = false;
    for (const Material& m : scene.materials) emits |= m.emissive();
    if (!emits) {  // a key light from above the camera's left shoulder
        Light key;
        key.direction = Vec3d(0.35, -0.6, -1.0).unitSafe();
        key.intensity = 3.0;
        scene.lights.push_back(key);
    }
    return scene;
}

Scene loadBuiltin(const std::string& name, double aspect) {
    if (isAnalyticSceneName(name)) return loadAnalyticBuiltin(name);
    if (name != "cloud" && name != "sphere")
        throw Error("unknown built-in scene 'builtin:" + name + "' (known: " + builtinSceneNames() + ")");
    Volume vol;
    vol.source = "procedural:" + name;
    vol.grid = makeProceduralGrid(name, name == "cloud" ? 128 : 64, 1);
    vol.name = vol.grid->getName();
    computeStatistics(vol);
    vol.tf = name == "cloud"
                 ? TransferFunction(0.0, 1.0, {{0.0, {0.25, 0.35, 0.7}, 0.0}, {0.25, {0.7, 0.75, 0.9}, 0.015}, {0.6, {1.0, 0.9, 0.75}, 0.06}, {1.0, {1.0, 0.7, 0.4}, 0.12}})
                 : TransferFunction(0.0, 1.0, {{0.0, {1, 1, 1}, 0.0}, {1.0, {1, 1, 1}, 0.05}});
    Scene scene = sceneAroundVolume(std::move(vol), "builtin:" + name, aspect);
    scene.camera.eye = scene.camera.target + Vec3d(0.6, 0.35, 1.25);  // three-quarter view
    return scene;
}

std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace

const char* builtinSceneNames() {
    return "builtin:cloud|builtin:sphere|builtin:zoneplate|builtin:grating|builtin:checker|builtin:siemens|builtin:lines|builtin:disc";
}

namespace {

Scene loadUncheckedScene(const std::string& input, std::optional<double> aspect, const std::string& gridName,
                         std::optional<int> frame, double limitBytes) {
    if (!gridName.empty() && lowerExtension(input) != ".vdb") throw Error("--grid applies to a bare .vdb input; a scene file names its grids itself");
    if (input.rfind("builtin:", 0) == 0) return loadBuiltin(input.substr(8), aspect.value_or(1.0));
    const std::string ext = lowerExtension(input);
    if (ext == ".vdb") return loadBareVdb(input, aspect.value_or(1.0), gridName, limitBytes);
    if (ext == ".obj" || ext == ".ply") return loadBareMesh(input, aspect.value_or(1.0), limitBytes);
    if (ext == ".json") {
        requireRegularFile(input, "scene");
        return loadJsonScene(input, aspect, frame, limitBytes);
    }
    throw Error("input '" + input + "': expected a scene .json, a .vdb, .obj or .ply file or " + builtinSceneNames());
}

}  // namespace

Scene loadSceneWithin(const std::string& input, std::optional<double> aspect, const std::string& gridName, std::optional<int> frame,
                      double limitBytes) {
    Scene scene = loadUncheckedScene(input, aspect, gridName, frame, limitBytes);
    requireSceneWithinWorld(scene);
    return scene;
}

Scene loadScene(const std::string& input, std::optional<double> aspect, const std::string& gridName,
                std::optional<int> frame) {
    return loadSceneWithin(input, aspect, gridName, frame, 0);
}

}  // namespace weft
