#pragma once
// The machine's physical memory, which the default memory limits are
// fractions of (header-only: the image codec module uses it too).
#include <unistd.h>

#include <cstdint>

namespace weft {

// Bytes of physical memory; 16 GiB when the system does not say.
inline double physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && size > 0 ? double(pages) * double(size) : double(std::uint64_t(16) << 30);
}

}  // namespace weft
