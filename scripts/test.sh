#!/usr/bin/env bash
# Builds weft and runs the whole default test suite with ctest.
# Slow sweeps are separate: scripts/test.sh --slow runs them as well.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
jobs=$(nproc 2>/dev/null || echo 2)
(cd build && ctest --output-on-failure -j"$jobs")
if [ "${1:-}" = "--slow" ] && [ -x build/bin/weft_slow_tests ]; then
  build/bin/weft_slow_tests
fi
