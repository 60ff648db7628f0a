#include "core/base/run/counters.hpp"

#include <algorithm>
#include <cstdio>

namespace weft {

namespace {

// Filled during static initialisation, in no fixed order: a function-local
// static exists before the first Counter registers.
std::vector<std::pair<std::string, std::string>>& registry() {
    static std::vector<std::pair<std::string, std::string>> all;
    return all;
}

}  // namespace

Counter::Counter(const char* name, const char* doc) : name_(name), doc_(doc) { registry().emplace_back(name, doc); }

IndexedCounter::IndexedCounter(const char* prefix, const char* doc) : prefix_(prefix), doc_(doc) {
    registry().emplace_back(std::string(prefix) + "<N>", doc);
}

std::vector<std::pair<std::string, std::string>> declaredCounters() {
    auto all = registry();
    std::sort(all.begin(), all.end());
    return all;
}

std::string declaredCountersMarkdown() {
    std::string out = "| counter | meaning |\n|---|---|\n";
    for (const auto& [name, doc] : declaredCounters()) out += "| `" + name + "` | " + doc + " |\n";
    return out;
}

const Counter kRaysCamera{"rays.camera", "camera rays (primary rays) traced, one per pixel sample or per column for slicing techniques"};
const Counter kRaysShadow{"rays.shadow", "shadow rays traced towards lights or VPLs"};
const Counter kRaysSurface{"rays.surface", "rays traced against the scene's meshes to find the surface behind a volume"};
const Counter kVolumeSamples{"volume.samples", "volume lookups (trilinear samples of the grids)"};
const Counter kVolumeLookups{"volume.lookups", "density reads of free flights, shadow rays and transmittance marches"};
const Counter kSlices{"slices", "slices (sampling planes) the volume was cut into"};
const Counter kCompositeOps{"composite.ops", "compositing operations (the paper's COMPOSITE)"};

void Counters::addNamed(std::string_view name, std::int64_t n) {
    CounterMap& local = perThread_.local();
    auto it = local.find(name);
    if (it == local.end()) local.emplace(std::string(name), n);
    else it->second += n;
}

CounterMap Counters::merged() const {
    CounterMap sum;
    for (const CounterMap& local : perThread_)
        for (const auto& [name, n] : local) sum[name] += n;
    return sum;
}

std::int64_t Counters::total(std::string_view name) const {
    std::int64_t sum = 0;
    for (const CounterMap& local : perThread_)
        if (auto it = local.find(name); it != local.end()) sum += it->second;
    return sum;
}

std::string Counters::table(const CounterMap& counters) {
    std::size_t width = 7;
    for (const auto& entry : counters) width = std::max(width, entry.first.size());
    std::string out;
    char line[256];
    for (const auto& [name, n] : counters) {
        std::snprintf(line, sizeof line, "  %-*s %16lld\n", static_cast<int>(width), name.c_str(),
                      static_cast<long long>(n));
        out += line;
    }
    return out;
}

}  // namespace weft
