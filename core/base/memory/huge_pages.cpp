#include "core/base/memory/huge_pages.hpp"

#include <cstdint>

#include <sys/mman.h>

namespace weft {

// A mapping 2 MiB longer than asked, trimmed at both ends to the boundary.
void* mapOnHugePages(std::size_t length, int prot, int flags) {
    void* raw = mmap(nullptr, length + kHugePageBytes, prot, flags, -1, 0);
    if (raw == MAP_FAILED) return raw;
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(raw);
    const std::uintptr_t aligned = (start + kHugePageBytes - 1) & ~std::uintptr_t(kHugePageBytes - 1);
    const std::size_t head = aligned - start, tail = kHugePageBytes - head;
    if (head) munmap(raw, head);
    if (tail) munmap(reinterpret_cast<void*>(aligned + length), tail);
    madvise(reinterpret_cast<void*>(aligned), length, MADV_HUGEPAGE);
    return reinterpret_cast<void*>(aligned);
}

}  // namespace weft
