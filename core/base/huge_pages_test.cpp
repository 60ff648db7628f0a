#include "core/base/huge_pages.hpp"

#include <gtest/gtest.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <fcntl.h>
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

TEST(HugePages, OnlyLargeAnonymousPrivateWritableRequestsSuitTheHeap) {
    const std::size_t big = kHugePageBytes, small = kHugePageBytes - 4096;
    EXPECT_TRUE(heapMappingSuitsHugePages(nullptr, big, kRw, kAnon, -1));
    EXPECT_TRUE(heapMappingSuitsHugePages(nullptr, big << 10, kRw, kAnon | MAP_NORESERVE, -1));
    EXPECT_FALSE(heapMappingSuitsHugePages(nullptr, small, kRw, kAnon, -1));                          // below 2 MiB
    EXPECT_FALSE(heapMappingSuitsHugePages(nullptr, big, PROT_READ, kAnon, -1));                      // read only
    EXPECT_FALSE(heapMappingSuitsHugePages(nullptr, big, PROT_NONE, kAnon, -1));                      // a reservation
    EXPECT_FALSE(heapMappingSuitsHugePages(nullptr, big, kRw | PROT_EXEC, kAnon, -1));                // code
    EXPECT_FALSE(heapMappingSuitsHugePages(nullptr, big, kRw, MAP_SHARED | MAP_ANONYMOUS, -1));       // shared
    EXPECT_FALSE(heapMappingSuitsHugePages(nullptr, big, kRw, MAP_PRIVATE, 3));                       // a file
    EXPECT_FALSE(heapMappingSuitsHugePages(nullptr, big, kRw, kAnon | MAP_STACK, -1));                // a thread's stack
    EXPECT_FALSE(heapMappingSuitsHugePages(nullptr, big, kRw, kAnon | MAP_HUGETLB, -1));              // hugetlbfs already
    EXPECT_FALSE(heapMappingSuitsHugePages(nullptr, big, kRw, kAnon | MAP_32BIT, -1));                // low addresses only
    EXPECT_FALSE(heapMappingSuitsHugePages(reinterpret_cast<void*>(kHugePageBytes), big, kRw, kAnon | MAP_FIXED, -1));
    EXPECT_FALSE(heapMappingSuitsHugePages(reinterpret_cast<void*>(kHugePageBytes), big, kRw, kAnon, -1));  // a hint
}

TEST(HugePages, TheHeapPutsLargeRequestsOnHugePagesAndMapsOthersAsAsked) {
    const std::int64_t before = heapMappingsOnHugePages();
    const std::size_t big = 3 * kHugePageBytes;
    void* heap = mapForHeap(nullptr, big, kRw, kAnon, -1, 0);
    ASSERT_NE(heap, MAP_FAILED);
    EXPECT_EQ(address(heap) % kHugePageBytes, 0u);
    EXPECT_EQ(heapMappingsOnHugePages(), before + 1);
    EXPECT_EQ(munmap(heap, big), 0);

    void* small = mapForHeap(nullptr, 8192, kRw, kAnon, -1, 0);  // as the kernel maps it
    ASSERT_NE(small, MAP_FAILED);
    static_cast<char*>(small)[8191] = 1;
    EXPECT_EQ(munmap(small, 8192), 0);
    EXPECT_EQ(heapMappingsOnHugePages(), before + 1);

    // A file maps its bytes, at the offset asked.
    char path[] = "/tmp/weft-huge-pages-XXXXXX";
    const int fd = mkstemp(path);
    ASSERT_GE(fd, 0);
    std::vector<char> bytes(8192, 'a');
    bytes[4096] = 'b';
    ASSERT_EQ(write(fd, bytes.data(), bytes.size()), ssize_t(bytes.size()));
    void* file = mapForHeap(nullptr, 4096, PROT_READ, MAP_PRIVATE, fd, 4096);
    ASSERT_NE(file, MAP_FAILED);
    EXPECT_EQ(static_cast<const char*>(file)[0], 'b');
    EXPECT_EQ(munmap(file, 4096), 0);
    close(fd);
    unlink(path);

    // A refusal comes back as the kernel's, errno and all.
    errno = 0;
    EXPECT_EQ(mapForHeap(nullptr, 4096, kRw, MAP_PRIVATE, -1, 0), MAP_FAILED);  // neither a file nor anonymous
    EXPECT_EQ(errno, EBADF);
}

}  // namespace
}  // namespace weft
