#include "hwsim/framebuffer.hpp"

#include <cstdint>

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace weft::hwsim {

void adviseHugePages(void* p, std::size_t bytes) {
#ifdef __linux__
    constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;
    const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(p) + kHugePage - 1) & ~(kHugePage - 1);
    const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(kHugePage - 1);
    if (p && begin < end) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // refused: small pages, as before
#else
    (void)p, (void)bytes;
#endif
}

}  // namespace weft::hwsim
