#pragma once
// Buffers of a frame's size (images, G-buffers, tables) on transparent huge
// pages. A buffer of small pages faults in 4 KiB at a time, and on a
// virtual machine each fault costs microseconds: a 256x256 deferred render
// spent a third of its time there, on whichever thread touched the page
// first, which capped its thread scaling. A 2 MiB-aligned mapping the
// kernel is asked to back with huge pages faults once per 2 MiB. Where the
// kernel declines (transparent huge pages off), small pages serve as before.
// A released buffer's mapping is kept for the next buffer of about its
// size (large_buffer.cpp), so the next frame finds its pages mapped.
//
// LargeBuffer<T> value-initialises like std::vector; FreshBuffer<T> leaves
// trivial elements uninitialised, for buffers a parallel loop fills whole
// (the first touch then happens on every thread at once).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace weft {

// Below this, the general allocator serves (rounding to 2 MiB would waste
// more than the faults cost).
constexpr std::size_t kLargeBufferBytes = std::size_t(1) << 20;

void* allocateLargePages(std::size_t bytes);  // throws std::bad_alloc
void releaseLargePages(void* p, std::size_t bytes) noexcept;
// Whether this thread's last allocateLargePages reused a released buffer's
// mapping (its contents are then that buffer's, not zero).
bool lastLargePagesReused();

template <class T, bool ValueInit>
struct LargePageAllocator {
    using value_type = T;
    static constexpr std::align_val_t kSmallAlignment{alignof(T) > 16 ? alignof(T) : 16};
    template <class U>
    struct rebind {
        using other = LargePageAllocator<U, ValueInit>;
    };
    LargePageAllocator() = default;
    template <class U>
    LargePageAllocator(const LargePageAllocator<U, ValueInit>&) noexcept {}

    T* allocate(std::size_t n) {
        const std::size_t bytes = n * sizeof(T);
        if (bytes >= kLargeBufferBytes) return static_cast<T*>(allocateLargePages(bytes));
        return static_cast<T*>(::operator new(bytes, kSmallAlignment));
    }
    void deallocate(T* p, std::size_t n) noexcept {
        const std::size_t bytes = n * sizeof(T);
        if (bytes >= kLargeBufferBytes) return releaseLargePages(p, bytes);
        ::operator delete(p, kSmallAlignment);
    }
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        if constexpr (ValueInit) ::new (static_cast<void*>(p)) U();
        else ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    friend bool operator==(const LargePageAllocator&, const LargePageAllocator&) { return true; }
    friend bool operator!=(const LargePageAllocator&, const LargePageAllocator&) { return false; }
};

template <class T>
using LargeBuffer = std::vector<T, LargePageAllocator<T, true>>;
template <class T>
using FreshBuffer = std::vector<T, LargePageAllocator<T, false>>;

// Loops over [0, n) in chunks on every thread, so that a fresh buffer's
// pages are first touched by all of them, not by one.
template <class Fn>
void forChunksInParallel(std::size_t n, const Fn& fn) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, std::size_t(1) << 14),
                      [&](const tbb::blocked_range<std::size_t>& r) { fn(r.begin(), r.end()); });
}

// Whether a fresh large mapping arrives zero-filled (an anonymous mapping).
#ifdef __linux__
constexpr bool kLargeBuffersArriveZeroed = true;
#else
constexpr bool kLargeBuffersArriveZeroed = false;
#endif

// n zero elements. A fresh large mapping is zero as the kernel hands it
// over, so no thread writes it here: the pass that fills it touches its
// pages first, on every thread at once, instead of one thread zeroing it
// all up front. A reused mapping is cleared on every thread.
template <class T>
FreshBuffer<T> zeroedBuffer(std::size_t n) {
    static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_copyable_v<T>);
    FreshBuffer<T> buffer(n);
    const bool large = n * sizeof(T) >= kLargeBufferBytes;
    if (!large && n) std::memset(buffer.data(), 0, n * sizeof(T));  // an empty vector's data() may be null
    else if (!kLargeBuffersArriveZeroed || lastLargePagesReused())
        forChunksInParallel(n, [&](std::size_t i0, std::size_t i1) { std::memset(buffer.data() + i0, 0, (i1 - i0) * sizeof(T)); });
    return buffer;
}

// Sets [begin, begin + n) to `value`, in parallel.
template <class T>
void fillInParallel(T* begin, std::size_t n, T value) {
    forChunksInParallel(n, [&](std::size_t i0, std::size_t i1) { std::fill(begin + i0, begin + i1, value); });
}

// n copies of `value`, written in parallel.
template <class T>
FreshBuffer<T> filledBuffer(std::size_t n, T value) {
    FreshBuffer<T> buffer(n);
    fillInParallel(buffer.data(), n, value);
    return buffer;
}

// A copy of `from`, written in parallel.
template <class T>
FreshBuffer<T> copiedBuffer(const FreshBuffer<T>& from) {
    FreshBuffer<T> to(from.size());
    forChunksInParallel(from.size(), [&](std::size_t i0, std::size_t i1) { std::copy(from.data() + i0, from.data() + i1, to.data() + i0); });
    return to;
}

}  // namespace weft
