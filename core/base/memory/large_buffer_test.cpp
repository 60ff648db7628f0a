#include "core/base/memory/large_buffer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>

namespace weft {
namespace {

constexpr std::size_t kLarge = (std::size_t(3) << 20) / sizeof(float) + 7;  // over the threshold, not a whole page

std::uintptr_t pastHugePage(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % (std::uintptr_t(2) << 20); }

TEST(LargeBuffer, LargeBuffersAreZeroedAndStartJustPastAHugePage) {
    LargeBuffer<float> big(kLarge);
    EXPECT_LT(pastHugePage(big.data()), 64u * 1024);  // a few cache lines past the boundary
    EXPECT_EQ(pastHugePage(big.data()) % 64, 0u);    // whole cache lines
    EXPECT_TRUE(std::all_of(big.begin(), big.end(), [](float v) { return v == 0.0f; }));
    big.back() = 5.0f;  // the last element is writable
    EXPECT_EQ(big.back(), 5.0f);
}

// Buffers read side by side at one index must not share their cache sets.
TEST(LargeBuffer, BuffersAllocatedTogetherStartAtDifferentOffsets) {
    FreshBuffer<float> a(kLarge), b(kLarge), c(kLarge);
    EXPECT_NE(pastHugePage(a.data()) % 4096, pastHugePage(b.data()) % 4096);
    EXPECT_NE(pastHugePage(b.data()) % 4096, pastHugePage(c.data()) % 4096);
    EXPECT_NE(pastHugePage(a.data()) % 4096, pastHugePage(c.data()) % 4096);
    c.back() = 1.0f;  // all of each is mapped
    EXPECT_EQ(c.back(), 1.0f);
}

TEST(LargeBuffer, SmallBuffersAndGrowthKeepValues) {
    LargeBuffer<int> v;
    for (int i = 0; i < int(kLarge); ++i) v.push_back(i);  // grows across the threshold
    ASSERT_EQ(v.size(), kLarge);
    EXPECT_EQ(v[12345], 12345);
    EXPECT_EQ(v.back(), int(kLarge) - 1);
    LargeBuffer<int> copy = v;
    EXPECT_EQ(copy, v);
}

TEST(LargeBuffer, FreshBufferHoldsWhatIsWritten) {
    FreshBuffer<double> fresh(kLarge);
    for (std::size_t i = 0; i < fresh.size(); ++i) fresh[i] = double(i) * 0.5;
    EXPECT_EQ(fresh[kLarge - 1], double(kLarge - 1) * 0.5);
    FreshBuffer<double> small(3, 1.5);  // an explicit value still fills
    EXPECT_EQ(small[2], 1.5);
}

TEST(LargeBuffer, ZeroedBuffersAreZeroLargeOrSmall) {
    for (const std::size_t n : {kLarge, std::size_t(5)}) {
        FreshBuffer<float> zero = zeroedBuffer<float>(n);
        ASSERT_EQ(zero.size(), n);
        EXPECT_TRUE(std::all_of(zero.begin(), zero.end(), [](float v) { return v == 0.0f; })) << n;
    }
    // a small buffer reuses the general allocator's memory, which a previous buffer dirtied
    { FreshBuffer<int> dirty(64, -1); }
    FreshBuffer<int> small = zeroedBuffer<int>(64);
    EXPECT_TRUE(std::all_of(small.begin(), small.end(), [](int v) { return v == 0; }));
}

std::uintptr_t hugePageOf(const void* p) { return reinterpret_cast<std::uintptr_t>(p) & ~((std::uintptr_t(2) << 20) - 1); }

// A released buffer's mapping serves the next buffer of about its size, so
// a frame sequence finds its pages mapped; what was left in it never shows
// through a buffer that promises zeros or values.
TEST(LargeBuffer, AReleasedMappingServesTheNextBufferOfItsSizeCleared) {
    std::uintptr_t first = 0;
    {
        FreshBuffer<float> dirty(kLarge, 7.0f);
        first = hugePageOf(dirty.data());
    }
    FreshBuffer<float> reused(kLarge);
    EXPECT_TRUE(lastLargePagesReused());
    EXPECT_EQ(hugePageOf(reused.data()), first);
    EXPECT_EQ(reused[kLarge / 2], 7.0f);  // what the last buffer left: a FreshBuffer promises no values
    reused = FreshBuffer<float>();
    FreshBuffer<float> zero = zeroedBuffer<float>(kLarge);
    EXPECT_TRUE(lastLargePagesReused());
    EXPECT_TRUE(std::all_of(zero.begin(), zero.end(), [](float v) { return v == 0.0f; }));
    std::fill(zero.begin(), zero.end(), 3.0f);
    zero = FreshBuffer<float>();
    LargeBuffer<float> valued(kLarge);
    EXPECT_TRUE(std::all_of(valued.begin(), valued.end(), [](float v) { return v == 0.0f; }));
}

// A buffer much smaller than a kept mapping does not take it (the mapping
// stays for a buffer of its own size), and one larger cannot.
TEST(LargeBuffer, KeptMappingsServeOnlyBuffersOfAboutTheirSize) {
    std::uintptr_t kept = 0;
    {
        FreshBuffer<float> big(4 * kLarge);
        big.back() = 1.0f;
        kept = hugePageOf(big.data());
    }
    FreshBuffer<float> small = zeroedBuffer<float>(kLarge);
    EXPECT_NE(hugePageOf(small.data()), kept);
    EXPECT_TRUE(std::all_of(small.begin(), small.end(), [](float v) { return v == 0.0f; }));
    FreshBuffer<float> larger = zeroedBuffer<float>(8 * kLarge);
    EXPECT_NE(hugePageOf(larger.data()), kept);
    larger.back() = 2.0f;  // all of it is mapped
    FreshBuffer<float> same = zeroedBuffer<float>(4 * kLarge);
    EXPECT_TRUE(lastLargePagesReused());
    EXPECT_EQ(hugePageOf(same.data()), kept);
    EXPECT_EQ(same.back(), 0.0f);
}

}  // namespace
}  // namespace weft
