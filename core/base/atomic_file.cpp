#include "core/base/atomic_file.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <atomic>
#include <cstring>

#include "core/base/error.hpp"

namespace fs = std::filesystem;

namespace weft {

namespace {

// Temporary files being written, for the signal handler: fixed slots of
// plain characters, because a handler may only call async-signal-safe
// functions (unlink) and must not allocate or lock.
constexpr std::size_t kSlots = 32, kPathMax = 4096;
std::array<std::array<char, kPathMax>, kSlots> liveTemps{};
std::array<std::atomic<bool>, kSlots> slotUsed{};

int claimSlot(const std::string& path) {
    if (path.size() >= kPathMax) return -1;
    for (std::size_t i = 0; i < kSlots; ++i) {
        bool expected = false;
        if (slotUsed[i].compare_exchange_strong(expected, true)) {
            std::memcpy(liveTemps[i].data(), path.c_str(), path.size() + 1);
            return int(i);
        }
    }
    return -1;  // more than kSlots outputs at once: that one is only removed by its destructor
}

void releaseSlot(int slot) {
    if (slot >= 0) slotUsed[std::size_t(slot)].store(false);
}

extern "C" void removeTempsAndReraise(int sig) {
    for (std::size_t i = 0; i < kSlots; ++i)
        if (slotUsed[i].load()) unlink(liveTemps[i].data());
    signal(sig, SIG_DFL);
    raise(sig);
}

// ".<stem>.weft-tmp-<pid><ext>": the pid of the process that wrote it.
std::string tempName(const fs::path& p, long pid) {
    return "." + p.stem().string() + ".weft-tmp-" + std::to_string(pid) + p.extension().string();
}

// Removes this output's temporary files whose writer no longer runs.
void removeStaleTemps(const fs::path& p) {
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    const std::string prefix = "." + p.stem().string() + ".weft-tmp-", ext = p.extension().string();
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind(prefix, 0) != 0 || name.size() <= prefix.size() + ext.size()) continue;
        const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - ext.size());
        if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) continue;
        const long pid = std::stol(digits);
        if (pid != getpid() && kill(pid_t(pid), 0) != 0 && errno == ESRCH) fs::remove(e.path(), ec);
    }
}

}  // namespace

void removeTemporaryOutputsOnInterrupt() {
    struct sigaction sa {};
    sa.sa_handler = removeTempsAndReraise;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

AtomicOutput::AtomicOutput(std::string finalPath) : final_(std::move(finalPath)) {
    const fs::path p(final_);
    removeStaleTemps(p);
    // The extension stays last so image writers pick the right format.
    temp_ = (p.parent_path() / tempName(p, getpid())).string();
    slot_ = claimSlot(temp_);
}

AtomicOutput::~AtomicOutput() {
    if (!committed_) std::remove(temp_.c_str());
    releaseSlot(slot_);
}

void AtomicOutput::commit() {
    // Fault-injection hook for the kill tests: hold the finished temporary
    // file this long before the rename, so a kill lands between the two.
    if (const char* ms = std::getenv("WEFT_TEST_PAUSE_BEFORE_RENAME_MS")) usleep(useconds_t(std::clamp(std::atoi(ms), 0, 60000)) * 1000);
    std::error_code ec;
    fs::rename(temp_, final_, ec);
    if (ec) throw Error("cannot write '" + final_ + "': " + ec.message());
    committed_ = true;
}

void writeTextAtomically(const std::string& path, const std::string& text, const std::string& what) {
    AtomicOutput file(path);
    std::ofstream os(file.tempPath(), std::ios::binary);
    os << text;
    os.close();
    if (!os) throw Error(what + " '" + path + "': write failed");
    file.commit();
}

void checkOutputPath(const std::string& path, const std::string& what) {
    if (path.empty()) throw Error(what + ": no output path given");
    const fs::path p(path);
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    if (!fs::is_directory(dir)) throw Error(what + " '" + path + "': folder '" + dir.string() + "' does not exist");
    if (access(dir.c_str(), W_OK) != 0) throw Error(what + " '" + path + "': folder '" + dir.string() + "' is not writable");
    if (fs::is_directory(p)) throw Error(what + " '" + path + "' is a folder");
}

}  // namespace weft
