#include "core/base/run/progress.hpp"

#include <algorithm>
#include <exception>

namespace weft {

Progress::Progress(std::string label, std::int64_t total, RenderMonitor* monitor)
    : label_(std::move(label)), total_(total > 0 ? total : 1), monitor_(monitor),
      start_(std::chrono::steady_clock::now()) {
    if (monitor_) monitor_->progress(label_, 0.0);
}

Progress::~Progress() {
    if (std::uncaught_exceptions() == 0) finish();
}

void Progress::advance(std::int64_t n) {
    throwIfInterrupted(monitor_);
    done_.fetch_add(n);
    if (!monitor_) return;
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                        std::chrono::steady_clock::now() - start_).count();
    std::int64_t last = lastReportMs_.load();
    if (ms - last >= 100 && lastReportMs_.compare_exchange_strong(last, ms))
        monitor_->progress(label_, std::min(1.0, double(done_.load()) / double(total_)));  // the latest count, not this thread's
}

void Progress::finish() {
    if (!monitor_ || finished_) return;
    finished_ = true;
    monitor_->progress(label_, 1.0);
}

}  // namespace weft
