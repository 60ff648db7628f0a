#pragma once
// What watches a render from outside it: the terminal's progress line, the
// Python module's callback and Ctrl-C, SIGINT/SIGTERM on the command line,
// a farm wrapper's deadline. The render reports how far each pass has come
// (core/base/run/progress.hpp) and polls interrupted() between rows, tiles and
// passes, as OpenVDB's tools poll their interrupter; once it answers yes,
// the render throws Cancelled and nothing is written.
#include <atomic>
#include <string_view>

#include "core/base/error.hpp"

namespace weft {

class Cancelled : public Error {
public:
    Cancelled() : Error("the render was cancelled") {}
};

class RenderMonitor {
public:
    virtual ~RenderMonitor() = default;
    // `fraction` in [0, 1] of the pass named `pass` is done. Called from any
    // of the render's threads, at most about ten times a second per pass,
    // and with 1 once when the pass ends.
    virtual void progress(std::string_view pass, double fraction) {}
    // Whether the render should stop. Polled often and from any thread: cheap.
    virtual bool interrupted() { return false; }
};

// A monitor another thread stops by setting a flag.
class CancelFlag : public RenderMonitor {
public:
    void request() { requested_.store(true, std::memory_order_relaxed); }
    bool interrupted() override { return requested_.load(std::memory_order_relaxed); }

private:
    std::atomic<bool> requested_{false};
};

inline void throwIfInterrupted(RenderMonitor* monitor) {
    if (monitor && monitor->interrupted()) throw Cancelled();
}

}  // namespace weft
