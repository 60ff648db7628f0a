#include "core/base/atomic_file.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <unistd.h>

#include "core/base/error.hpp"

namespace fs = std::filesystem;

namespace weft {

AtomicOutput::AtomicOutput(std::string finalPath) : final_(std::move(finalPath)) {
    const fs::path p(final_);
    // The extension stays last so image writers pick the right format.
    temp_ = (p.parent_path() / ("." + p.stem().string() + ".weft-tmp-" + std::to_string(getpid()) +
                                p.extension().string())).string();
}

AtomicOutput::~AtomicOutput() {
    if (!committed_) std::remove(temp_.c_str());
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

void checkOutputPath(const std::string& path, const std::string& what) {
    if (path.empty()) throw Error(what + ": no output path given");
    const fs::path p(path);
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    if (!fs::is_directory(dir)) throw Error(what + " '" + path + "': folder '" + dir.string() + "' does not exist");
    if (access(dir.c_str(), W_OK) != 0) throw Error(what + " '" + path + "': folder '" + dir.string() + "' is not writable");
    if (fs::is_directory(p)) throw Error(what + " '" + path + "' is a folder");
}

}  // namespace weft
