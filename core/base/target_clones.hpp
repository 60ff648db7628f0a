#pragma once
// Function multiversioning: one clone per instruction set, chosen by an
// ifunc resolver when the program loads. Left out of ThreadSanitizer builds,
// whose instrumented resolvers would run before the TSan runtime is set up
// and crash the process at load.
#if defined(__SANITIZE_THREAD__)
#define WEFT_TARGET_CLONES(...)
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define WEFT_TARGET_CLONES(...)
#endif
#endif
#ifndef WEFT_TARGET_CLONES
#define WEFT_TARGET_CLONES(...) __attribute__((target_clones(__VA_ARGS__)))
#endif
