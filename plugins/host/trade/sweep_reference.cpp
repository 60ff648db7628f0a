#include "plugins/host/trade/sweep_reference.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/base/error.hpp"
#include "core/image/io/image_io.hpp"
#include "core/scene/scene.hpp"
#include "plugins/technique.hpp"

namespace weft {

namespace {

namespace fs = std::filesystem;

// FNV-1a, 64 bits: stable across runs and machines (std::hash is not).
struct Fnv {
    std::uint64_t h = 1469598103934665603ull;
    Fnv& add(std::string_view s) {
        for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
        h = (h ^ 0xff) * 1099511628211ull;  // separates consecutive fields
        return *this;
    }
};

// A file's bytes for small files (scene JSON), its size and time otherwise:
// a changed file changes the hash without reading gigabytes of grids.
void addFile(Fnv& f, const std::string& path) {
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    if (ec) return (void)f.add(path);
    f.add(path).add(std::to_string(size));
    if (size > (1u << 20)) {
        f.add(std::to_string(fs::last_write_time(path, ec).time_since_epoch().count()));
        return;
    }
    std::ifstream in(path, std::ios::binary);
    f.add(std::string(std::istreambuf_iterator<char>(in), {}));
}

std::string hex(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

}  // namespace

SweepReferences::SweepReferences(std::string spec, std::string cacheDir) : spec_(std::move(spec)), cacheDir_(std::move(cacheDir)) {}

void SweepReferences::check(const std::vector<SweepRun>& runs, const Scene& scene) {
    if (!automatic()) {
        const Image& ref = readOnce(spec_);
        for (const SweepRun& run : runs)
            if (run.width != ref.width() || run.height != ref.height())
                throw Error("--reference '" + spec_ + "' is " + std::to_string(ref.width()) + "x" + std::to_string(ref.height()) +
                            " but run " + std::to_string(run.index + 1) + " (" + run.technique + " " + runLabel(run) + ") renders " +
                            std::to_string(run.width) + "x" + std::to_string(run.height));
        return;
    }
    for (const SweepRun& run : runs) {
        try {
            checkRender(referenceRequest(run, scene), scene);
        } catch (const Error& e) {
            throw Error("--reference auto for " + run.technique + ": " + e.what());
        }
    }
}

RenderRequest SweepReferences::referenceRequest(const SweepRun& run, const Scene& scene) const {
    const ConvergedReference& ref = techniques().get(run.technique).reference;
    if (ref.technique.empty())
        throw Error(run.technique + " declares no converged reference: give --reference REF.exr");
    RenderRequest r = run.request;
    if (ref.technique != run.technique) r.sets.clear();  // the run's parameters belong to its own technique
    for (const auto& [key, value] : run.varied) {         // the swept values are not the reference's
        std::erase(r.sets, key + "=" + value);
        if (key == "seed") r.seed.reset();                 // one reference for every seed
    }
    r.technique = ref.technique;
    r.sets.insert(r.sets.end(), ref.sets.begin(), ref.sets.end());
    r.spp = ref.spp;
    if (!scene.meshes.empty())
        for (const TechniqueInfo* t : techniques().all()) r.spp = std::max(*r.spp, t->reference.spp);
    return r;
}

std::string SweepReferences::cachePath(const SweepRun& run, const Scene& scene) const {
    const RenderRequest r = referenceRequest(run, scene);
    const EffectiveRender q = effectiveRender(r, scene.render);
    Fnv f;
    f.add(WEFT_VERSION).add(q.technique).add(q.resolution.text()).add(std::to_string(q.spp)).add(std::to_string(q.seed));
    for (const std::string& s : q.sets) f.add(s);
    f.add(r.grid).add(r.frame ? std::to_string(*r.frame) : "-");
    addFile(f, r.input);
    for (const Volume& v : scene.volumes) addFile(f, v.source);
    for (const TriangleMesh& m : scene.meshes) addFile(f, m.source);
    return (fs::path(cacheDir_) / ("reference-" + hex(f.h) + ".exr")).string();
}

const Image& SweepReferences::readOnce(const std::string& path) {
    auto it = loaded_.find(path);
    if (it == loaded_.end()) it = loaded_.emplace(path, readImage(path)).first;
    return it->second;
}

std::string SweepReferences::ensurePath(const SweepRun& run, const LoadedScene& scene) {
    const std::string path = automatic() ? cachePath(run, *scene.scene) : spec_;
    if (automatic() && !loaded_.count(path) && !fs::exists(path)) {
        RenderRequest r = referenceRequest(run, *scene.scene);
        r.output = path;
        fs::create_directories(cacheDir_);
        const RenderOutcome out = renderLoadedScene(r, scene);
        writeExr(out.image, path, out.metadata, out.window);
    }
    return path;
}

const Image& SweepReferences::imageFor(const SweepRun& run, const LoadedScene& scene) {
    return readOnce(ensurePath(run, scene));
}

const TradeReference& SweepReferences::measureFor(const SweepRun& run, const LoadedScene& scene) {
    const std::string path = ensurePath(run, scene);
    auto it = prepared_.find(path);
    if (it == prepared_.end()) it = prepared_.try_emplace(path, readOnce(path)).first;
    return it->second;
}

}  // namespace weft
