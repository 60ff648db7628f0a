#pragma once
// Helpers shared by the tests: run the weft binary, temporary folders, and
// small scenes written on the fly.
#include <filesystem>
#include <string>

#include "core/base/error.hpp"

namespace weft::test {

struct CommandResult {
    int status = -1;       // exit status
    std::string output;    // stdout and stderr together
};

// Runs `weft ARGS` through the shell and captures what it printed.
CommandResult runWeft(const std::string& args, const std::string& env = "");

// A fresh folder under the system temp dir, removed when the object dies.
class TempDir {
public:
    TempDir();
    ~TempDir();
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

void writeText(const std::filesystem::path& path, const std::string& text);
std::string readBytes(const std::filesystem::path& path);
// The shared datasets folder next to the project (../shared/data), or "" if absent.
std::string sharedDataDir();

// The message of the weft::Error that f() throws, "" when it throws none.
template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace weft::test
