#!/usr/bin/env bash
# `make fuzz FUZZ_SECONDS=N`: builds the libFuzzer targets (tests/fuzz, in
# build-sanitize/ with ASan and UBSan, the build `make test-sanitize` uses)
# and runs each for N seconds (default 60), then prints executions and
# findings per target. FUZZ_TARGETS="obj ply" runs only those; FUZZ_RUNS=M
# stops a target after M executions (its N seconds still bound it);
# FUZZ_BUILD=0 runs the targets as built (a long campaign beside edits);
# FUZZ_FLAGS adds libFuzzer flags, e.g. FUZZ_FLAGS=-detect_leaks=0 for vdb,
# where every corrupt file makes OpenVDB leak (lsan.supp) and each leak
# costs a full leak scan: 60 executions a second instead of 400.
# Under build-sanitize/fuzz/: seeds/ (written once), corpus/<target>/ (what
# the runs found interesting, kept between runs), findings/<target>/ (the
# inputs that crashed, leaked or hung), logs/<target>.log.
# Exit status 1 when any target has a finding.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/sanitize-env.sh
seconds="${FUZZ_SECONDS:-60}"
runs_limit="${FUZZ_RUNS:--1}"
# The targets of tests/fuzz/CMakeLists.txt.
read -r -a targets <<<"${FUZZ_TARGETS:-scene_json vdb obj ply raw nrrd npy vtk exr text}"

if [ "${FUZZ_BUILD:-1}" != 0 ]; then
  weft_configure_sanitize
  cmake --build "$WEFT_SANITIZE_DIR" -j"$(weft_jobs)" --target weft_fuzz_all
fi
bin="$WEFT_SANITIZE_DIR/bin"
work="$WEFT_SANITIZE_DIR/fuzz"
mkdir -p "$work/logs"
if [ ! -d "$work/seeds" ]; then
  "$bin/weft_fuzz_seeds" "$work/seeds.tmp" "$PWD"
  mv "$work/seeds.tmp" "$work/seeds"
fi

dictionary() {
  case "$1" in
    scene_json) echo "-dict=tests/fuzz/scene.dict" ;;
    obj) echo "-dict=tests/fuzz/obj.dict" ;;
    ply) echo "-dict=tests/fuzz/ply.dict" ;;
  esac
}

# libFuzzer's final statistics line "stat::NAME: VALUE".
stat() { sed -n "s/^stat::$2: *//p" "$1" | tail -1; }

status=0
printf '%-12s %14s %10s %9s  %s\n' target executions exec/s findings result
for t in "${targets[@]}"; do
  mkdir -p "$work/corpus/$t" "$work/findings/$t"
  log="$work/logs/$t.log"
  start="$work/logs/$t.start"
  touch "$start"
  rc=0
  # -timeout 10: an input that takes longer is a hang (issue 14's bound).
  # shellcheck disable=SC2046,SC2086
  "$bin/fuzz_$t" -max_total_time="$seconds" -runs="$runs_limit" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 ${FUZZ_FLAGS:-} \
    -artifact_prefix="$work/findings/$t/" $(dictionary "$t") "$work/corpus/$t" "$work/seeds/$t" >"$log" 2>&1 || rc=$?
  runs=$(stat "$log" number_of_executed_units)
  rate=$(stat "$log" average_exec_per_sec)
  # A run that stops on a finding prints no final statistics: its last
  # status line ("#N ...") counts the executions.
  [ -n "$runs" ] || runs=$(sed -n 's/^#\([0-9]*\).*/\1/p' "$log" | tail -1)
  found=$(find "$work/findings/$t" -type f -newer "$start" | wc -l)
  result=ok
  if [ "$rc" -ne 0 ] || [ "$found" -gt 0 ]; then
    result="FINDING (exit $rc, see $log)"
    status=1
  fi
  printf '%-12s %14s %10s %9s  %s\n' "$t" "${runs:-?}" "${rate:-?}" "$found" "$result"
done
exit "$status"
