#!/usr/bin/env bash
# Builds weft with clang, AddressSanitizer and UndefinedBehaviorSanitizer
# into build-sanitize/ (the same build the fuzz targets use) and runs the
# default test suite under them. Any sanitizer report fails its test.
# WEFT_JOBS sets the parallelism (default: all cores).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/sanitize-env.sh
weft_configure_sanitize
jobs=$(weft_jobs)
# weft_tests pulls in everything ctest runs: weft, the image codec module,
# the example plugin and the Mesa cross-check program.
cmake --build "$WEFT_SANITIZE_DIR" -j"$jobs" --target weft_tests
(cd "$WEFT_SANITIZE_DIR" && ctest --output-on-failure -j"$jobs" "$@")
