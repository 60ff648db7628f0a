#include "core/base/input_file.hpp"

#include <filesystem>

#include "core/base/error.hpp"

namespace weft {

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
}

}  // namespace weft
