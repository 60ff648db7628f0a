// Linked into the executables of sanitized builds only (cmake/Sanitize.cmake).
// Under AddressSanitizer (and ThreadSanitizer), operator new aborts the process when a request is
// too large instead of throwing std::bad_alloc, so a corrupt file that makes
// a library (OpenVDB's blosc reader, say) ask for 8 EB would end a sanitized
// run that a normal build survives: glibc refuses it, the exception reaches
// weft's handler and the user reads one line. These replacements keep the
// normal build's behaviour: a request above kLimit throws std::bad_alloc.
// 1 GiB is below libFuzzer's malloc limit (its -rss_limit_mb, 2 GiB in
// scripts/fuzz.sh), which would otherwise report the request as a finding.
// They allocate with malloc and free with free, which ASan still checks for
// overflows, use after free and leaks.
#include <cstddef>
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kLimit = std::size_t(1) << 30;

void* allocate(std::size_t n, std::size_t align = 0) {
    if (n > kLimit) return nullptr;
    if (align <= alignof(std::max_align_t)) return std::malloc(n ? n : 1);
    void* p = nullptr;
    return posix_memalign(&p, align, n ? n : 1) == 0 ? p : nullptr;
}

void* allocateOrThrow(std::size_t n, std::size_t align = 0) {
    if (void* p = allocate(n, align)) return p;
    throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t n) { return allocateOrThrow(n); }
void* operator new[](std::size_t n) { return allocateOrThrow(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void* operator new(std::size_t n, std::align_val_t a) { return allocateOrThrow(n, std::size_t(a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return allocateOrThrow(n, std::size_t(a)); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept { return allocate(n, std::size_t(a)); }
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept { return allocate(n, std::size_t(a)); }

void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
