# Sourced by scripts/test-sanitize.sh and scripts/fuzz.sh: the clang build in
# build-sanitize/ and the sanitizer settings its programs run with.
# (ctest, the tests' child `weft` processes and gtest discovery at build time
# inherit them.)

WEFT_SANITIZE_DIR="${WEFT_SANITIZE_DIR:-build-sanitize}"
_weft_supp="$PWD/scripts/sanitizers"

# Reports must fail: ASan exits non-zero by default; halt_on_error makes
# UBSan do the same (the build also has -fno-sanitize-recover). Leak
# checking stays on; lsan.supp names the library leaks we cannot fix.
export ASAN_OPTIONS="check_initialization_order=1:detect_leaks=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$_weft_supp/ubsan.supp:${UBSAN_OPTIONS:-}"
export LSAN_OPTIONS="suppressions=$_weft_supp/lsan.supp:print_suppressions=0:${LSAN_OPTIONS:-}"
export ASAN_SYMBOLIZER_PATH="${ASAN_SYMBOLIZER_PATH:-$(command -v llvm-symbolizer || true)}"

# Debian's clang and its compiler-rt (libclang-rt-14-dev) must both be there.
weft_check_clang() {
  if ! command -v clang++ >/dev/null; then
    echo "sanitize: clang++ not found (apt-get install clang libclang-rt-dev)" >&2
    return 1
  fi
  local rt
  rt="$(clang++ -print-resource-dir)/lib/linux"
  for lib in asan ubsan_standalone fuzzer; do
    if [ ! -f "$rt/libclang_rt.$lib-x86_64.a" ]; then
      echo "sanitize: $rt/libclang_rt.$lib-x86_64.a is missing (apt-get install libclang-rt-dev)" >&2
      return 1
    fi
  done
}

# A clang Release build at -O1 in directory $1, configured once with the
# cmake options that follow: -O1 keeps the build and the runs quick while
# the reports still point at lines.
weft_configure_clang() {
  local dir=$1
  shift
  export CCACHE_BASEDIR="$PWD"
  if [ ! -f "$dir/CMakeCache.txt" ]; then
    cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
      -DCMAKE_C_FLAGS_RELEASE="-O1 -gline-tables-only -DNDEBUG" \
      -DCMAKE_CXX_FLAGS_RELEASE="-O1 -gline-tables-only -DNDEBUG" \
      -DWEFT_BUILD_BENCH=OFF -DWEFT_PCH=OFF "$@"
  fi
}

# One configuration for both the sanitized suite and the fuzzers.
weft_configure_sanitize() {
  weft_check_clang
  weft_configure_clang "$WEFT_SANITIZE_DIR" -DWEFT_FUZZ=ON
}

weft_jobs() { echo "${WEFT_JOBS:-$(nproc 2>/dev/null || echo 2)}"; }
