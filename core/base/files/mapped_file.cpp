#include "core/base/files/mapped_file.hpp"

#include <sys/mman.h>

namespace weft {

MappedFile::MappedFile(int fd, std::uint64_t size) {
    if (size == 0) return;
    void* at = mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (at != MAP_FAILED) data_ = static_cast<const char*>(at), size_ = size;
}

MappedFile::~MappedFile() {
    if (data_) munmap(const_cast<char*>(data_), size_);
}

}  // namespace weft
