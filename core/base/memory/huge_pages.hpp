#pragma once
// Anonymous memory on transparent huge pages, for weft's own large buffers
// (large_buffer.hpp: frame buffers, G-buffers, tables). On small pages each
// 4 KiB is a fault when first written, about 10 us apiece on the virtual
// machines weft's figures come from; on a 2 MiB boundary with the kernel
// asked for huge pages, one fault serves 2 MiB. The kernel honours the
// request when transparent huge pages are `always` or `madvise` and
// otherwise maps small pages.
//
// The heap is left to the allocator and to the machine's settings
// (docs/usage.md, memory): transparent huge pages `always`, glibc's
// glibc.malloc.hugetlb tunable, TBB_MALLOC_USE_HUGE_PAGES.
#include <cstddef>

namespace weft {

constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

// `length` bytes of fresh anonymous private memory (`prot`, `flags` as
// mmap's, MAP_PRIVATE | MAP_ANONYMOUS among them), starting on a 2 MiB
// boundary, with the kernel asked to back it with huge pages. MAP_FAILED
// (errno set) where the kernel has no room.
void* mapOnHugePages(std::size_t length, int prot, int flags);

}  // namespace weft
