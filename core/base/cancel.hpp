#pragma once
// Stopping a render from outside it: the caller (the Python module on
// Ctrl-C, a wrapper with a deadline) sets the flag; the render polls it
// between rows and tiles (core/base/progress.hpp polls on every advance)
// and ends by throwing Cancelled, so that nothing is written.
#include <atomic>

#include "core/base/error.hpp"

namespace weft {

class Cancelled : public Error {
public:
    Cancelled() : Error("the render was cancelled") {}
};

struct CancelFlag {
    std::atomic<bool> requested{false};
};

inline void throwIfCancelled(const CancelFlag* flag) {
    if (flag && flag->requested.load(std::memory_order_relaxed)) throw Cancelled();
}

}  // namespace weft
