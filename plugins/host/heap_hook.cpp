// Linked into the weft executable only (not the Python module, the tests or
// sanitized builds, whose runtime intercepts mmap itself). Defining mmap
// here puts the process's heap on huge pages (core/base/huge_pages.hpp):
// the executable comes first in the dynamic linker's search, so the
// allocator's and the libraries' calls to mmap arrive here, as an
// LD_PRELOAD library's would. TBB's allocator asks the kernel for huge
// pages only when they are on for every process (`always`); this asks for
// them per mapping, as the frame buffers do.
#include "core/base/huge_pages.hpp"

extern "C" {

void* mmap(void* addr, std::size_t length, int prot, int flags, int fd, off_t offset) {
    return weft::mapForHeap(addr, length, prot, flags, fd, offset);
}

void* mmap64(void* addr, std::size_t length, int prot, int flags, int fd, off_t offset) {
    return weft::mapForHeap(addr, length, prot, flags, fd, offset);
}

}  // extern "C"
