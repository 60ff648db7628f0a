#pragma once
// Writing outputs without ever leaving a partial file: write to a temporary
// name in the destination folder, then rename over the final name (atomic on
// POSIX). A failed or interrupted write never touches an existing file, and
// a temporary file left by a process that died (SIGKILL, power loss) is
// removed by the next write of the same output.
#include <string>

namespace weft {

class AtomicOutput {
public:
    explicit AtomicOutput(std::string finalPath);
    ~AtomicOutput();  // removes the temporary file unless commit() succeeded
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;

    // Where to write; same folder and extension as the final path.
    const std::string& tempPath() const { return temp_; }
    void commit();

private:
    std::string final_;
    std::string temp_;
    bool committed_ = false;
    int slot_ = -1;  // in the table the interrupt handler cleans
};

// Removes the temporary files being written, for a signal handler that is
// about to end the process (async-signal-safe: unlink only).
void removeTemporaryOutputsNow() noexcept;

// Writes `text` to `path` through an AtomicOutput; a failed write throws
// "<what> '<path>': write failed" and leaves no file. An existing FIFO or
// character device is written into instead.
void writeTextAtomically(const std::string& path, const std::string& text, const std::string& what);

// What an output is: a file (an image, a volume: always replaced whole
// through a temporary) or text (statistics, tables), which may also go into
// an existing FIFO or character device such as /dev/stdout.
enum class OutputKind { File, Text };

// Fails early (before a long render) when the output cannot be written:
// missing folder, a folder of that name, then checkOutputTarget.
void checkOutputPath(const std::string& path, const std::string& what, OutputKind kind = OutputKind::File);

// Fails when the output would destroy something: it names an input of this
// job (by identity, core/base/files/input_file.hpp), or a device, FIFO or socket
// (text may go into a FIFO or character device); or when its file name is
// longer than a file system allows.
void checkOutputTarget(const std::string& path, const std::string& what, OutputKind kind);

}  // namespace weft
