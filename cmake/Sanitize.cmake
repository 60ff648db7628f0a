# Sanitized builds (scripts/test-sanitize.sh, scripts/fuzz.sh; both use
# build-sanitize/). Off by default: the gcc build is unaffected.
#   WEFT_SANITIZE  AddressSanitizer + UndefinedBehaviorSanitizer over all of
#                  weft; a UBSan report aborts (-fno-sanitize-recover), so it
#                  fails the test that triggered it.
#   WEFT_FUZZ      also libFuzzer's coverage instrumentation, and the fuzz
#                  targets of tests/fuzz. The instrumentation needs no
#                  runtime beyond the sanitizers', so the test suite built
#                  this way runs as well: one clang build serves both.
#   WEFT_TSAN      ThreadSanitizer instead (scripts/test-tsan.sh, build-tsan/):
#                  the weft executable and the loader tests, whose files are
#                  read by several threads at once.
# Debian's libraries (OpenVDB, TBB, Embree, OIIO...) are not instrumented;
# ASan still sees their heap through its malloc.
option(WEFT_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer (clang)" OFF)
option(WEFT_FUZZ "Build the libFuzzer targets of tests/fuzz (clang; implies WEFT_SANITIZE)" OFF)
option(WEFT_TSAN "Build with ThreadSanitizer (clang; not with WEFT_SANITIZE)" OFF)
if(WEFT_FUZZ)
  set(WEFT_SANITIZE ON)
endif()
if(WEFT_SANITIZE AND WEFT_TSAN)
  message(FATAL_ERROR "WEFT_TSAN and WEFT_SANITIZE/WEFT_FUZZ exclude each other (one sanitizer runtime per process)")
endif()
# Any sanitizer runtime owns malloc and intercepts mmap: neither TBB's
# allocator proxy nor the Python module goes into such a build.
if(WEFT_SANITIZE OR WEFT_TSAN)
  set(WEFT_INSTRUMENTED ON)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "WEFT_SANITIZE/WEFT_FUZZ/WEFT_TSAN need clang (configure with -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang)")
  endif()
else()
  set(WEFT_INSTRUMENTED OFF)
endif()
if(WEFT_TSAN)
  set(WEFT_SANITIZE_FLAGS -fsanitize=thread -fno-omit-frame-pointer)
  add_compile_options(${WEFT_SANITIZE_FLAGS})
  add_link_options(${WEFT_SANITIZE_FLAGS})
  # No bounded operator new here: TSan's runtime defines every operator new
  # and delete strongly (linked whole), so a replacement clashes with it. A
  # request above TSan's allocation limit ends the process instead of
  # throwing std::bad_alloc.
endif()
if(WEFT_SANITIZE)
  set(WEFT_SANITIZE_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  # Reports inside Debian's library headers, one entry each with why.
  add_compile_options(${WEFT_SANITIZE_FLAGS} -fsanitize-ignorelist=${CMAKE_SOURCE_DIR}/scripts/sanitizers/ubsan-ignorelist.txt)
  add_link_options(${WEFT_SANITIZE_FLAGS})
  # Every executable gets operator new that throws for absurd sizes, as a
  # normal build's does (cmake/sanitize_bounded_new.cpp says why).
  set(WEFT_SANITIZE_EXE_SOURCES ${CMAKE_SOURCE_DIR}/cmake/sanitize_bounded_new.cpp)
endif()
if(WEFT_FUZZ)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
