#pragma once
// Shared by the fuzz targets (tests/fuzz/*_target.hpp) and their regression
// tests in the default suite: an input either goes through weft's function
// (accepted) or is refused with a weft::Error (rejected). Anything else that
// leaves the function (another exception type, a crash, a sanitizer report,
// a hang) is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "core/base/error.hpp"

namespace weft::fuzz {

struct Outcome {
    bool accepted = false;
    std::string message;  // the weft::Error's text when rejected
    bool skipped = false; // legitimate but too slow to fuzz (see the target)
};

template <class Fn>
Outcome guarded(Fn&& fn) {
    try {
        fn();
        return {true, ""};
    } catch (const Error& e) {
        return {false, e.what()};
    }
}

// A property of an accepted input that does not hold: a finding, reported
// the way a sanitizer reports one (libFuzzer saves the input).
[[noreturn]] inline void propertyFailed(const char* what, std::string_view detail) {
    std::fprintf(stderr, "fuzz property failed: %s: %.*s\n", what, int(detail.size()), detail.data());
    std::abort();
}
inline void require(bool ok, const char* what, std::string_view detail = {}) {
    if (!ok) propertyFailed(what, detail);
}

// One folder per process for the files the loaders read (they take paths),
// removed when the process ends normally.
struct ScratchDir {
    std::filesystem::path path;
    ScratchDir() : path(std::filesystem::temp_directory_path() / ("weft-fuzz-" + std::to_string(getpid()))) {
        std::filesystem::create_directories(path);
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
};
inline const std::filesystem::path& scratchDir() {
    static const ScratchDir dir;
    return dir.path;
}

inline std::string writeScratch(const std::string& name, std::string_view bytes) {
    const std::filesystem::path path = scratchDir() / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
    return path.string();
}

inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

}  // namespace weft::fuzz
