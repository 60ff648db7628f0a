#!/usr/bin/env bash
# Builds the weft executable and the loader tests with clang and
# ThreadSanitizer into build-tsan/, and runs them over a ThreadSanitizer
# build of the installed oneTBB (scripts/tsan-tbb.sh says why). The loaders read scene
# files, volumes and meshes on several threads at once; a race report in the
# tests or in any weft process they start fails the run.
# WEFT_JOBS sets the parallelism (default: all cores); arguments go to the
# test binary (e.g. --gtest_filter='CorruptVdb.*').
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/sanitize-env.sh
weft_check_clang
rt="$(clang++ -print-resource-dir)/lib/linux"
if [ ! -f "$rt/libclang_rt.tsan-x86_64.a" ]; then
  echo "test-tsan: $rt/libclang_rt.tsan-x86_64.a is missing (apt-get install libclang-rt-dev)" >&2
  exit 1
fi
dir=build-tsan
weft_configure_clang "$dir" -DWEFT_TSAN=ON
cmake --build "$dir" -j"$(weft_jobs)" --target weft_loader_tests
tbb_lib=$(WEFT_JOBS="$(weft_jobs)" bash scripts/tsan-tbb.sh "$PWD/$dir")
export LD_LIBRARY_PATH="$tbb_lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
if ! ldd "$dir/bin/weft_loader_tests" | grep -F "$tbb_lib/libtbb.so.12" >/dev/null; then
  echo "test-tsan: the tests would not load the instrumented $tbb_lib/libtbb.so.12" >&2
  exit 1
fi
# Reports go to files, one per process: a child weft's report counts too,
# whatever exit status its test expected.
reports="$PWD/$dir/tsan-reports"
rm -rf "$reports" && mkdir -p "$reports"
export TSAN_OPTIONS="log_path=$reports/report:second_deadlock_stack=1:suppressions=$PWD/scripts/sanitizers/tsan.supp:${TSAN_OPTIONS:-}"
status=0
"$dir/bin/weft_loader_tests" "$@" || status=$?
if compgen -G "$reports/report.*" >/dev/null; then
  cat "$reports"/report.* >&2
  echo "test-tsan: ThreadSanitizer reported in $(ls "$reports" | wc -l) process(es)" >&2
  exit 1
fi
[ "$status" -eq 0 ] && echo "test-tsan: the loader tests pass with no ThreadSanitizer report"
exit "$status"
