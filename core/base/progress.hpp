#pragma once
// Progress on a terminal: a single updating line on stderr while work runs,
// nothing at all when stderr is not a TTY (farm logs stay clean). Each
// advance polls the render's cancel flag, so a loop that reports progress
// stops within a step of a cancel (core/base/cancel.hpp).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

#include "core/base/cancel.hpp"

namespace weft {

class Progress {
public:
    Progress(std::string label, std::int64_t total, bool enabled, const CancelFlag* cancel = nullptr);
    ~Progress();
    // Thread-safe; redraws at most ten times a second; throws Cancelled once the flag is set.
    void advance(std::int64_t n = 1);
    void finish();
    // Whether progress should be shown by default (stderr is a terminal).
    static bool terminalAttached();

private:
    void draw(std::int64_t done);
    std::string label_;
    std::int64_t total_;
    bool enabled_;
    const CancelFlag* cancel_;
    bool finished_ = false;
    std::atomic<std::int64_t> done_{0};
    std::atomic<std::int64_t> lastDrawMs_{-1000};
    std::chrono::steady_clock::time_point start_;
};

}  // namespace weft
