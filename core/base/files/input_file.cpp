#include "core/base/files/input_file.hpp"

#include <sys/stat.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <utility>

#include "core/base/error.hpp"

namespace weft {

namespace {

using FileIdentity = std::pair<dev_t, ino_t>;

struct InputRecord {
    std::string path, what;
    bool ofJob = false;  // read while a job ran: forgotten when the last job running ends
};

// Inputs by identity; loaders on several threads record into it.
struct InputRegistry {
    std::mutex mutex;
    std::map<FileIdentity, InputRecord> inputs;
    int jobsRunning = 0;
};

InputRegistry& registry() {
    static InputRegistry r;
    return r;
}

bool identityOf(const std::string& path, FileIdentity& id) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return false;
    id = {st.st_dev, st.st_ino};
    return true;
}

void recordInput(const std::string& path, const std::string& what) {
    FileIdentity id;
    if (!identityOf(path, id)) return;
    InputRegistry& r = registry();
    std::lock_guard lock(r.mutex);
    r.inputs.emplace(id, InputRecord{path, what, r.jobsRunning > 0});
}

}  // namespace

void requireRegularFile(const std::string& path, const std::string& what) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    const std::string name = what + " '" + path + "': ";
    if (ec == std::errc::too_many_symbolic_link_levels) throw Error(name + "is a loop of symbolic links");
    if (ec == std::errc::permission_denied) throw Error(name + "permission denied");
    if (ec || st.type() == fs::file_type::not_found) {
        std::error_code lec;
        if (fs::is_symlink(fs::symlink_status(path, lec)))
            throw Error(name + "is a symbolic link to '" + fs::read_symlink(path, lec).string() + "', which does not exist");
        throw Error(name + "no such file");
    }
    if (st.type() == fs::file_type::directory) throw Error(name + "is a directory, not a file");
    if (st.type() == fs::file_type::fifo) throw Error(name + "is a FIFO (named pipe); give a regular file");
    if (st.type() != fs::file_type::regular) throw Error(name + "is a device or socket, not a regular file");
    recordInput(path, what);
}

void refuseInputAsOutput(const std::string& path, const std::string& what) {
    FileIdentity id;
    if (!identityOf(path, id)) return;
    InputRegistry& r = registry();
    std::lock_guard lock(r.mutex);
    const auto it = r.inputs.find(id);
    if (it == r.inputs.end()) return;
    const InputRecord& in = it->second;
    const std::string same = in.path == path ? "" : " ('" + in.path + "')";
    throw Error(what + " '" + path + "' is the " + in.what + same + " this run reads; write the " + what +
                " to another file");
}

bool sameExistingFile(const std::string& a, const std::string& b) {
    FileIdentity ia, ib;
    return identityOf(a, ia) && identityOf(b, ib) && ia == ib;
}

InputJob::InputJob() {
    InputRegistry& r = registry();
    std::lock_guard lock(r.mutex);
    ++r.jobsRunning;
}

InputJob::~InputJob() {
    InputRegistry& r = registry();
    std::lock_guard lock(r.mutex);
    if (--r.jobsRunning > 0) return;
    std::erase_if(r.inputs, [](const auto& entry) { return entry.second.ofJob; });
}

}  // namespace weft
