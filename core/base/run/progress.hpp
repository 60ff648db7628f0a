#pragma once
// How far one loop of a render has come, reported to the render's monitor
// (core/base/run/render_monitor.hpp) at most ten times a second. Each advance
// polls the monitor, so a loop that reports progress stops within a step
// of an interrupt.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

#include "core/base/run/render_monitor.hpp"

namespace weft {

class Progress {
public:
    Progress(std::string label, std::int64_t total, RenderMonitor* monitor);
    ~Progress();
    // Thread-safe; throws Cancelled once the monitor says the render is interrupted.
    void advance(std::int64_t n = 1);
    // Reports the loop whole (also done by the destructor, unless unwinding).
    void finish();

private:
    std::string label_;
    std::int64_t total_;
    RenderMonitor* monitor_;
    bool finished_ = false;
    std::atomic<std::int64_t> done_{0};
    std::atomic<std::int64_t> lastReportMs_{-1000};
    std::chrono::steady_clock::time_point start_;
};

}  // namespace weft
