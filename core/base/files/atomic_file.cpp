#include "core/base/files/atomic_file.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>  // kill(pid, 0): is a temporary file's writer alive
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <atomic>
#include <cstring>

#include "core/base/error.hpp"
#include "core/base/files/input_file.hpp"

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

constexpr std::size_t kNameMax = NAME_MAX, kPidDigits = 10;

// ".<stem>.weft-tmp-": the stem cut so that the whole temporary name, with
// any pid and the extension, stays within NAME_MAX bytes (a legal 254-byte
// output name must not fail for its temporary's sake).
std::string tempPrefix(const fs::path& p) {
    const std::string stem = p.stem().string(), ext = p.extension().string();
    const std::size_t fixed = std::strlen("..weft-tmp-") + kPidDigits + ext.size();
    const std::size_t keep = fixed < kNameMax ? std::min(stem.size(), kNameMax - fixed) : 0;
    return "." + stem.substr(0, keep) + ".weft-tmp-";
}

// "<prefix><pid><ext>": the pid of the process that wrote it.
std::string tempName(const fs::path& p, long pid) { return tempPrefix(p) + std::to_string(pid) + p.extension().string(); }

// Removes this output's temporary files whose writer no longer runs.
void removeStaleTemps(const fs::path& p) {
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    const std::string prefix = tempPrefix(p), ext = p.extension().string();
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

// A FIFO or a character device (a terminal, /dev/stdout, /dev/null): text is
// written into it, as cp would, never replaced by a regular file.
bool isStreamTarget(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode));
}

// Streams opened when their output was checked, before the render: a FIFO
// nobody reads is refused then, not after the other outputs are written;
// one that is read stays open (closing it would end the reader's input).
std::mutex openStreamsMutex;
std::map<std::string, int> openStreams;

int openStream(const std::string& path, const std::string& what) {
    {
        std::lock_guard lock(openStreamsMutex);
        if (const auto it = openStreams.find(path); it != openStreams.end()) return it->second;
    }
    // Non-blocking open: a FIFO nobody reads fails at once instead of hanging.
    const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        const int err = errno;
        throw Error(what + " '" + path + "': " + (err == ENXIO ? "a FIFO that nobody reads" : std::strerror(err)));
    }
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    std::lock_guard lock(openStreamsMutex);
    return openStreams.emplace(path, fd).first->second;
}

void writeToStream(const std::string& path, const std::string& text, const std::string& what) {
    const int fd = openStream(path, what);
    {
        std::lock_guard lock(openStreamsMutex);
        openStreams.erase(path);
    }
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int err = errno;
            ::close(fd);
            throw Error(what + " '" + path + "': write failed: " + std::strerror(err));
        }
        done += std::size_t(n);
    }
    ::close(fd);
}

}  // namespace

void removeTemporaryOutputsNow() noexcept {
    for (std::size_t i = 0; i < kSlots; ++i)
        if (slotUsed[i].load()) unlink(liveTemps[i].data());
}

AtomicOutput::AtomicOutput(std::string finalPath) : final_(std::move(finalPath)) {
    checkOutputTarget(final_, "output", OutputKind::File);
    // Through a symbolic link, the file it names is replaced (as cp writes
    // through it): renaming over the link itself would replace the link.
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(final_, ec))) {
        const fs::path target = fs::weakly_canonical(final_, ec);
        if (!ec) final_ = target.string();
    }
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
    refuseInputAsOutput(final_, "output");  // an input read after the output was opened
    std::error_code ec;
    fs::rename(temp_, final_, ec);
    if (ec) throw Error("cannot write '" + final_ + "': " + ec.message());
    committed_ = true;
}

void writeTextAtomically(const std::string& path, const std::string& text, const std::string& what) {
    if (isStreamTarget(path)) return writeToStream(path, text, what);
    AtomicOutput file(path);
    std::ofstream os(file.tempPath(), std::ios::binary);
    os << text;
    os.close();
    if (!os) throw Error(what + " '" + path + "': write failed: " + std::strerror(errno));
    file.commit();
}

void checkOutputPath(const std::string& path, const std::string& what, OutputKind kind) {
    if (path.empty()) throw Error(what + ": no output path given");
    if (kind == OutputKind::Text && isStreamTarget(path)) return (void)openStream(path, what);  // written into, in whatever folder
    const fs::path p(path);
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw Error(what + " '" + path + "': folder '" + dir.string() + "' does not exist");
    if (access(dir.c_str(), W_OK) != 0) throw Error(what + " '" + path + "': folder '" + dir.string() + "' is not writable");
    checkOutputTarget(path, what, kind);
    if (fs::is_directory(p, ec)) throw Error(what + " '" + path + "' is a folder");
}

void checkOutputTarget(const std::string& path, const std::string& what, OutputKind kind) {
    const std::string name = fs::path(path).filename().string();
    if (name.size() > kNameMax)
        throw Error(what + " '" + path + "': its file name is " + std::to_string(name.size()) + " bytes, above the " +
                    std::to_string(kNameMax) + " a file system allows");
    if (path.size() >= PATH_MAX) throw Error(what + " '" + path.substr(0, 64) + "...': the path is longer than the system allows");
    struct stat st {};
    const bool exists = ::stat(path.c_str(), &st) == 0, stream = exists && (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode));
    if (exists && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode) && !(kind == OutputKind::Text && stream))
        throw Error(what + " '" + path + "' is a device, FIFO or socket; give a regular file (text outputs such as --stats "
                    "may go to a FIFO or a terminal)");
    refuseInputAsOutput(path, what);
}

}  // namespace weft
