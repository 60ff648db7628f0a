#pragma once
// What a technique receives besides the scene and its parameters: image
// size, samples per pixel, seed, the counters to add to, timings of its
// passes, and the monitor it reports progress to and polls for interrupts.
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/base/run/render_monitor.hpp"
#include "core/base/run/counters.hpp"

namespace weft {

struct RenderSettings {
    int width = 512;
    int height = 512;
    int spp = 1;
    std::uint64_t seed = 0;
    // Rows a tiled render needs, [rowBegin, rowEnd); rowEnd < 0 means all.
    // The image plane (core/sampling/image_plane.hpp) skips the others.
    int rowBegin = 0;
    int rowEnd = -1;
    // Told the progress of each loop (core/base/run/progress.hpp) and polled
    // between rows and passes (ScopedTimer); null: nobody watches.
    RenderMonitor* monitor = nullptr;
};

// Named wall-clock durations of passes, in the order they ran. Every timed
// pass starts by polling the render's monitor (core/base/run/render_monitor.hpp).
class Timings {
public:
    void add(const std::string& name, double ms) { entries_.emplace_back(name, ms); }
    const std::vector<std::pair<std::string, double>>& entries() const { return entries_; }
    RenderMonitor* monitor = nullptr;

private:
    std::vector<std::pair<std::string, double>> entries_;
};

// Adds the lifetime of the scope to a Timings entry; throws Cancelled
// instead of starting when the render was interrupted.
class ScopedTimer {
public:
    ScopedTimer(Timings& timings, std::string name)
        : timings_(timings), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {
        throwIfInterrupted(timings.monitor);
    }
    ~ScopedTimer() {
        timings_.add(name_, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count());
    }

private:
    Timings& timings_;
    std::string name_;
    std::chrono::steady_clock::time_point start_;
};

struct RenderContext {
    RenderSettings settings;
    Counters counters;
    Timings timings;
};

}  // namespace weft
