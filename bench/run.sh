#!/usr/bin/env bash
# Runs every benchmark; each prints its ratios measured side by side in one run.
set -euo pipefail
cd "$(dirname "$0")/.."
build/bin/hwsim_throughput
python3 bench/kraus_tables.py "$@"
