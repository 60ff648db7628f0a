#pragma once
// Anonymous memory on transparent huge pages, for frame buffers
// (large_buffer.hpp) and for the weft process's heap (plugins/host/heap_hook.cpp).
//
// The heap: the allocator (TBB's, in the weft process) takes memory from the
// kernel in mappings of a few MiB and hands out OpenVDB's leaves, the
// oracles' fields and every vector from them. On small pages each 4 KiB is
// a fault when first written, 10 us apiece on the virtual machines these
// figures come from (a 14 MB volume: 3,500 faults, 36 ms); on a 2 MiB
// boundary with the kernel asked for huge pages, one fault serves 2 MiB.
// The kernel honours the request when transparent huge pages are `always`
// or `madvise` and otherwise maps small pages, as before. Where it must
// first compact memory to find a huge page (THP defrag `madvise`, on a
// fragmented machine) a first touch may wait; WEFT_HEAP_HUGE_PAGES=0 turns
// the heap's part off.
#include <cstddef>
#include <cstdint>

#include <sys/types.h>

namespace weft {

constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

// `length` bytes of fresh anonymous private memory (`prot`, `flags` as
// mmap's, MAP_PRIVATE | MAP_ANONYMOUS among them), starting on a 2 MiB
// boundary, with the kernel asked to back it with huge pages. MAP_FAILED
// (errno set) where the kernel has no room.
void* mapOnHugePages(std::size_t length, int prot, int flags);

// Whether an mmap request is heap memory worth huge pages: anonymous,
// private, readable and writable, no address asked for, at least 2 MiB.
bool heapMappingSuitsHugePages(const void* addr, std::size_t length, int prot, int flags, int fd);

// mmap as the weft process's hook serves it: a request that suits huge
// pages on them (unless WEFT_HEAP_HUGE_PAGES=0 is in the environment),
// every other one as the kernel maps it.
void* mapForHeap(void* addr, std::size_t length, int prot, int flags, int fd, off_t offset);

// The heap mappings mapForHeap has put on huge pages in this process.
std::int64_t heapMappingsOnHugePages();

}  // namespace weft
