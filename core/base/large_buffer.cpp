#include "core/base/large_buffer.hpp"

#include <atomic>
#include <cstdint>

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace weft {

namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;

std::size_t roundedToHugePages(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }

}  // namespace

#ifdef __linux__

namespace {

// Where a buffer starts past its 2 MiB boundary: buffers read side by side
// at one index (a pyramid's data, distances and rays) would otherwise share
// their cache sets and evict each other. Steps of 9 cache lines spread them
// over the sets of L1 and L2.
constexpr std::size_t kColourStep = 9 * 64, kColours = 32;

std::size_t nextColour() {
    static std::atomic<std::size_t> count{0};
    return count.fetch_add(1, std::memory_order_relaxed) % kColours * kColourStep;
}

}  // namespace

// An anonymous mapping trimmed to a 2 MiB boundary (huge pages need the
// alignment), then the hint; a refused hint leaves small pages. The buffer
// starts a few cache lines past the boundary (nextColour).
void* allocateLargePages(std::size_t bytes) {
    const std::size_t colour = nextColour(), length = roundedToHugePages(colour + bytes);
    void* raw = mmap(nullptr, length + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(raw);
    const std::uintptr_t aligned = (start + kHugePage - 1) & ~std::uintptr_t(kHugePage - 1);
    const std::size_t head = aligned - start, tail = kHugePage - head;
    if (head) munmap(raw, head);
    if (tail) munmap(reinterpret_cast<void*>(aligned + length), tail);
    madvise(reinterpret_cast<void*>(aligned), length, MADV_HUGEPAGE);
    return reinterpret_cast<void*>(aligned + colour);
}

void releaseLargePages(void* p, std::size_t bytes) noexcept {
    if (!p) return;
    const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(p), start = at & ~std::uintptr_t(kHugePage - 1);
    munmap(reinterpret_cast<void*>(start), roundedToHugePages(at - start + bytes));
}

#else

void* allocateLargePages(std::size_t bytes) { return ::operator new(bytes, std::align_val_t(64)); }
void releaseLargePages(void* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t(64)); }

#endif

}  // namespace weft
