#include "core/base/progress.hpp"

#include <cstdio>
#include <unistd.h>

namespace weft {

Progress::Progress(std::string label, std::int64_t total, bool enabled, const CancelFlag* cancel)
    : label_(std::move(label)), total_(total > 0 ? total : 1), enabled_(enabled), cancel_(cancel),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { finish(); }

bool Progress::terminalAttached() { return isatty(STDERR_FILENO) == 1; }

void Progress::advance(std::int64_t n) {
    throwIfCancelled(cancel_);
    const std::int64_t done = done_.fetch_add(n) + n;
    if (!enabled_) return;
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                        std::chrono::steady_clock::now() - start_).count();
    std::int64_t last = lastDrawMs_.load();
    if (ms - last >= 100 && lastDrawMs_.compare_exchange_strong(last, ms)) draw(done);
}

void Progress::draw(std::int64_t done) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "\r%s %5.1f%%  %6.1fs", label_.c_str(), 100.0 * double(done) / double(total_), seconds);
    std::fflush(stderr);
}

void Progress::finish() {
    if (!enabled_ || finished_) return;
    finished_ = true;
    draw(total_);
    std::fputc('\n', stderr);
}

}  // namespace weft
