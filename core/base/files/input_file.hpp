#pragma once
// Input files are checked before a library opens them: a directory, a FIFO
// (which would block forever) or a device such as /dev/zero (which never
// ends) is named as what it is, not reported as "no such file" or left to
// hang the render.
//
// Every input that passes is remembered by its identity (device and inode,
// links followed), so that no output of the same job can replace it: the
// scene named again as --stats, a tile named as the merge's output. Outputs
// are compared by identity, not by spelling (core/base/files/atomic_file.hpp).
#include <string>

namespace weft {

// Throws weft::Error "<what> '<path>': ..." unless path is a regular file
// (symbolic links are followed). Records the file as an input of this job.
void requireRegularFile(const std::string& path, const std::string& what);

// Throws "<what> '<path>' is the <input what> '<input path>' ..." when path
// names an existing file that this job reads. A path that does not exist is
// no input.
void refuseInputAsOutput(const std::string& path, const std::string& what);

// Whether both paths name one existing file (links and hard links followed).
bool sameExistingFile(const std::string& a, const std::string& b);

// One job's inputs (a render of the command line or of a batch): what is read
// while jobs run is forgotten when the last of them ends, so a file an
// earlier job read may be written by a later one. Inputs read outside any
// job (a batch file, weft merge, filter, convert) are kept for the life of
// the process.
class InputJob {
public:
    InputJob();
    ~InputJob();
    InputJob(const InputJob&) = delete;
    InputJob& operator=(const InputJob&) = delete;
};

}  // namespace weft
