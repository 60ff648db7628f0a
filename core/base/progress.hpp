#pragma once
// Progress on a terminal: a single updating line on stderr while work runs,
// nothing at all when stderr is not a TTY (farm logs stay clean).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

namespace weft {

class Progress {
public:
    Progress(std::string label, std::int64_t total, bool enabled);
    ~Progress();
    // Thread-safe; redraws at most ten times a second.
    void advance(std::int64_t n = 1);
    void finish();
    // Whether progress should be shown by default (stderr is a terminal).
    static bool terminalAttached();

private:
    void draw(std::int64_t done);
    std::string label_;
    std::int64_t total_;
    bool enabled_;
    bool finished_ = false;
    std::atomic<std::int64_t> done_{0};
    std::atomic<std::int64_t> lastDrawMs_{-1000};
    std::chrono::steady_clock::time_point start_;
};

}  // namespace weft
