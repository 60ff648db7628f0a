#include "core/base/huge_pages.hpp"

#include <atomic>
#include <cstdlib>
#include <cstring>

#include <sys/mman.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace weft {

namespace {

// The kernel's mmap itself: this file serves the process's mmap hook, so a
// call through the C library's name would come back here.
void* kernelMmap(void* addr, std::size_t length, int prot, int flags, int fd, off_t offset) {
    return reinterpret_cast<void*>(syscall(SYS_mmap, addr, length, prot, flags, fd, offset));
}

std::atomic<std::int64_t> heapMappings{0};

bool heapHugePagesWanted() {
    static const bool wanted = [] {
        const char* v = std::getenv("WEFT_HEAP_HUGE_PAGES");
        return !(v && std::strcmp(v, "0") == 0);
    }();
    return wanted;
}

}  // namespace

// A mapping 2 MiB longer than asked, trimmed at both ends to the boundary.
void* mapOnHugePages(std::size_t length, int prot, int flags) {
    void* raw = kernelMmap(nullptr, length + kHugePageBytes, prot, flags, -1, 0);
    if (raw == MAP_FAILED) return raw;
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(raw);
    const std::uintptr_t aligned = (start + kHugePageBytes - 1) & ~std::uintptr_t(kHugePageBytes - 1);
    const std::size_t head = aligned - start, tail = kHugePageBytes - head;
    if (head) munmap(raw, head);
    if (tail) munmap(reinterpret_cast<void*>(aligned + length), tail);
    madvise(reinterpret_cast<void*>(aligned), length, MADV_HUGEPAGE);
    return reinterpret_cast<void*>(aligned);
}

bool heapMappingSuitsHugePages(const void* addr, std::size_t length, int prot, int flags, int fd) {
    constexpr int kShape = MAP_PRIVATE | MAP_ANONYMOUS;
    constexpr int kRefused = MAP_SHARED | MAP_FIXED | MAP_FIXED_NOREPLACE | MAP_STACK | MAP_HUGETLB | MAP_GROWSDOWN | MAP_32BIT;
    return !addr && fd == -1 && (flags & kShape) == kShape && !(flags & kRefused) && prot == (PROT_READ | PROT_WRITE) &&
           length >= kHugePageBytes;
}

void* mapForHeap(void* addr, std::size_t length, int prot, int flags, int fd, off_t offset) {
    if (heapMappingSuitsHugePages(addr, length, prot, flags, fd) && heapHugePagesWanted()) {
        void* p = mapOnHugePages(length, prot, flags);
        if (p != MAP_FAILED) {
            heapMappings.fetch_add(1, std::memory_order_relaxed);
            return p;
        }
    }
    return kernelMmap(addr, length, prot, flags, fd, offset);
}

std::int64_t heapMappingsOnHugePages() { return heapMappings.load(std::memory_order_relaxed); }

}  // namespace weft
