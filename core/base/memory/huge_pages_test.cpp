#include "core/base/memory/huge_pages.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include <sys/mman.h>
#include <unistd.h>

namespace weft {
namespace {

constexpr int kRw = PROT_READ | PROT_WRITE, kAnon = MAP_PRIVATE | MAP_ANONYMOUS;

std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }

// Whether [p, p + 4 KiB) is mapped (mincore fails with ENOMEM where nothing is).
bool mapped(const void* p) {
    unsigned char resident = 0;
    return mincore(const_cast<void*>(p), 4096, &resident) == 0;
}

// The VmFlags line of /proc/self/smaps for the mapping that holds p.
std::string vmFlagsOf(const void* p) {
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        unsigned long lo = 0, hi = 0;
        if (std::sscanf(line.c_str(), "%lx-%lx ", &lo, &hi) == 2)  // a mapping's first line
            inside = address(p) >= lo && address(p) < hi;
        if (inside && line.rfind("VmFlags:", 0) == 0) return line;
    }
    return "";
}

bool kernelHasTransparentHugePages() { return access("/sys/kernel/mm/transparent_hugepage/enabled", F_OK) == 0; }

TEST(HugePages, MappingStartsOnA2MiBBoundaryIsZeroWritableAndExactlyAsLong) {
    const std::size_t length = (std::size_t(3) << 20) + 3 * 4096;  // not a whole number of huge pages
    auto* p = static_cast<unsigned char*>(mapOnHugePages(length, kRw, kAnon));
    ASSERT_NE(p, MAP_FAILED);
    EXPECT_EQ(address(p) % kHugePageBytes, 0u);
    bool zero = true;
    for (std::size_t i = 0; i < length; i += 4096) zero = zero && p[i] == 0 && p[i + 4095] == 0;
    EXPECT_TRUE(zero);
    p[length - 1] = 7;  // the last byte asked for is there
    EXPECT_EQ(p[length - 1], 7);
    EXPECT_FALSE(mapped(p + length));  // the 2 MiB of slack past it went back
    if (kernelHasTransparentHugePages()) {
        EXPECT_NE(vmFlagsOf(p).find(" hg"), std::string::npos) << vmFlagsOf(p);
    }
    EXPECT_EQ(munmap(p, length), 0);  // unmapped as asked, as the allocator will
    EXPECT_FALSE(mapped(p));
}

}  // namespace
}  // namespace weft
