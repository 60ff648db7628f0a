#include "core/image/io/half_pixels.hpp"

#include <algorithm>
#include <cmath>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#include <immintrin.h>
#define WEFT_HAVE_F16C_PATH 1
#endif

namespace weft {

Imath::half toHalfSaturated(float v) {
    const float top = float(HALF_MAX);
    return Imath::half(std::isnan(v) ? 0.0f : std::clamp(v, -top, top));
}

namespace {

#if WEFT_HAVE_F16C_PATH
// Built for F16C and AVX whatever the compiler's target; called only when the CPU has both.
__attribute__((target("avx,f16c"))) std::size_t toHalfF16c(const float* in, std::size_t count, Imath::half* out) {
    const __m256 top = _mm256_set1_ps(float(HALF_MAX)), bottom = _mm256_set1_ps(-float(HALF_MAX));
    std::size_t i = 0;
    for (; i + 8 <= count; i += 8) {
        __m256 v = _mm256_loadu_ps(in + i);
        v = _mm256_andnot_ps(_mm256_cmp_ps(v, v, _CMP_UNORD_Q), v);  // NaN -> +0
        v = _mm256_max_ps(_mm256_min_ps(v, top), bottom);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), _mm256_cvtps_ph(v, _MM_FROUND_TO_NEAREST_INT));
    }
    return i;
}

// AVX (which the compiler's check also confirms the OS saves) and F16C (CPUID leaf 1, ECX).
bool cpuHasF16c() {
    static const bool has = [] {
        unsigned a = 0, b = 0, c = 0, d = 0;
        return __builtin_cpu_supports("avx") && __get_cpuid(1, &a, &b, &c, &d) && (c & bit_F16C);
    }();
    return has;
}
#endif

}  // namespace

void toHalfSaturated(const float* in, std::size_t count, Imath::half* out) {
    std::size_t done = 0;
#if WEFT_HAVE_F16C_PATH
    if (cpuHasF16c()) done = toHalfF16c(in, count, out);
#endif
    for (std::size_t i = done; i < count; ++i) out[i] = toHalfSaturated(in[i]);
}

}  // namespace weft
