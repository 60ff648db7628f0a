#include "core/base/memory/large_buffer.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#ifdef __linux__
#include <sys/mman.h>
#include <unistd.h>
#endif

#include "core/base/memory/huge_pages.hpp"

namespace weft {

namespace {

std::size_t roundedToHugePages(std::size_t bytes) { return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes; }

}  // namespace

#ifdef __linux__

namespace {

thread_local bool lastReused = false;

// Mappings released by one buffer, kept for the next of about their size.
// On a virtual machine a fresh page costs far more than writing memory
// already mapped (measured here: 0.35 GB/s for 4 KiB pages, 1-12 GB/s for
// huge pages, against 20-38 GB/s), and a frame sequence, a sweep or a
// Python session allocates the same frame-sized buffers frame after frame.
// At most kKeptMappings and a sixteenth of physical memory (1 GiB at most)
// are kept, the oldest given back first.
class KeptMappings {
public:
    // The shortest kept mapping of `length` to 5/4 `length` bytes, the
    // latest released of those (its pages the likeliest still cached),
    // trimmed to `length`; 0 if none.
    std::uintptr_t take(std::size_t length) {
        std::lock_guard<std::mutex> lock(mutex_);
        std::size_t best = kept_.size();
        for (std::size_t k = 0; k < kept_.size(); ++k)
            if (kept_[k].length >= length && kept_[k].length <= length + length / 4 && (best == kept_.size() || kept_[k].length <= kept_[best].length))
                best = k;
        if (best == kept_.size()) return 0;
        const Mapping m = kept_[best];
        kept_.erase(kept_.begin() + std::ptrdiff_t(best));
        bytes_ -= m.length;
        if (m.length > length) munmap(reinterpret_cast<void*>(m.start + length), m.length - length);
        return m.start;
    }
    void keep(std::uintptr_t start, std::size_t length) {
        std::vector<Mapping> out;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (length > limit()) {
                out.push_back({start, length});
            } else {
                kept_.push_back({start, length});
                bytes_ += length;
                while (kept_.size() > kKeptMappings || bytes_ > limit()) {
                    out.push_back(kept_.front());
                    bytes_ -= kept_.front().length;
                    kept_.erase(kept_.begin());
                }
            }
        }
        for (const Mapping& m : out) munmap(reinterpret_cast<void*>(m.start), m.length);
    }

private:
    struct Mapping {
        std::uintptr_t start;
        std::size_t length;
    };
    static constexpr std::size_t kKeptMappings = 16;
    static std::size_t limit() {
        static const std::size_t bytes = [] {
            const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
            const std::size_t physical = pages > 0 && size > 0 ? std::size_t(pages) * std::size_t(size) : 0;
            return std::min(std::size_t(1) << 30, physical / 16);
        }();
        return bytes;
    }
    std::mutex mutex_;
    std::vector<Mapping> kept_;  // oldest first
    std::size_t bytes_ = 0;
};

KeptMappings& keptMappings() {
    static KeptMappings* kept = new KeptMappings;  // never destroyed: buffers may be released during exit
    return *kept;
}

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

// A kept mapping of about the size, or a fresh one on huge pages
// (huge_pages.hpp; where the kernel declines, small pages). The buffer
// starts a few cache lines past the 2 MiB boundary (nextColour).
void* allocateLargePages(std::size_t bytes) {
    const std::size_t colour = nextColour(), length = roundedToHugePages(colour + bytes);
    if (const std::uintptr_t kept = keptMappings().take(length)) {
        lastReused = true;
        return reinterpret_cast<void*>(kept + colour);
    }
    lastReused = false;
    void* aligned = mapOnHugePages(length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS);
    if (aligned == MAP_FAILED) throw std::bad_alloc();
    return static_cast<char*>(aligned) + colour;
}

void releaseLargePages(void* p, std::size_t bytes) noexcept {
    if (!p) return;
    const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(p), start = at & ~std::uintptr_t(kHugePageBytes - 1);
    keptMappings().keep(start, roundedToHugePages(at - start + bytes));
}

bool lastLargePagesReused() { return lastReused; }

#else

void* allocateLargePages(std::size_t bytes) { return ::operator new(bytes, std::align_val_t(64)); }
void releaseLargePages(void* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t(64)); }
bool lastLargePagesReused() { return true; }

#endif

}  // namespace weft
