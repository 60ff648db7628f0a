#include "plugins/host/command_line_monitor.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

#include <signal.h>
#include <unistd.h>

#include "core/base/files/atomic_file.hpp"

namespace weft {

namespace {

// Lock-free atomics: the handler reads and writes them.
std::atomic<int> rendersRunning{0};
std::atomic<int> receivedSignal{0};
static_assert(std::atomic<int>::is_always_lock_free);

// Ends the process by `sig`'s default action. Inside its own handler the
// signal is blocked, so it is unblocked first, or raise() would only leave
// it pending. Async-signal-safe.
[[noreturn]] void endBy(int sig) {
    signal(sig, SIG_DFL);
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, sig);
    sigprocmask(SIG_UNBLOCK, &set, nullptr);
    raise(sig);
    _exit(128 + sig);  // not reached: the default action of SIGINT/SIGTERM ends the process
}

extern "C" void onStopSignal(int sig) {
    int none = 0;
    if (rendersRunning.load() > 0 && receivedSignal.compare_exchange_strong(none, sig)) return;
    removeTemporaryOutputsNow();
    endBy(sig);
}

// One line per pass, redrawn in place: "<pass>  42.0%   3.1s".
class CommandLineMonitor : public RenderMonitor {
public:
    void progress(std::string_view pass, double fraction) override {
        if (!terminal_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        const auto now = std::chrono::steady_clock::now();
        if (pass != pass_) pass_ = std::string(pass), start_ = now;
        const double seconds = std::chrono::duration<double>(now - start_).count();
        std::fprintf(stderr, "\r%s %5.1f%%  %6.1fs%s", pass_.c_str(), 100.0 * fraction, seconds, fraction >= 1.0 ? "\n" : "");
        if (fraction >= 1.0) pass_.clear();
        std::fflush(stderr);
    }
    bool interrupted() override { return receivedSignal.load(std::memory_order_relaxed) != 0; }

private:
    const bool terminal_ = stderrIsTerminal();
    std::mutex mutex_;
    std::string pass_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace

void installStopSignalHandlers() {
    struct sigaction sa {};
    sa.sa_handler = onStopSignal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

RenderMonitor& commandLineMonitor() {
    static CommandLineMonitor monitor;
    return monitor;
}

bool stderrIsTerminal() { return isatty(STDERR_FILENO) == 1; }

RenderRunning::RenderRunning() { rendersRunning.fetch_add(1); }
RenderRunning::~RenderRunning() { rendersRunning.fetch_sub(1); }

void endBySignalIfReceived() {
    const int sig = receivedSignal.load();
    if (!sig) return;
    if (stderrIsTerminal()) std::fputc('\n', stderr);  // below a progress line
    std::fprintf(stderr, "weft: %s: the render stopped and wrote nothing\n", sig == SIGINT ? "interrupted (SIGINT)" : "terminated (SIGTERM)");
    endBy(sig);
}

}  // namespace weft
