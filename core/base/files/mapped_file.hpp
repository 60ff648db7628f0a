#pragma once
// A file's bytes mapped read-only for as long as the object lives: only the
// pages that are read are loaded, and threads read them without system calls.
#include <cstddef>
#include <cstdint>

namespace weft {

class MappedFile {
public:
    // Maps the first `size` bytes of the open file `fd` (which may be closed
    // afterwards); empty when size is 0 or the system cannot map it.
    MappedFile(int fd, std::uint64_t size);
    ~MappedFile();
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;

    explicit operator bool() const { return data_ != nullptr; }
    const char* data() const { return data_; }
    std::size_t size() const { return size_; }

private:
    const char* data_ = nullptr;
    std::size_t size_ = 0;
};

}  // namespace weft
