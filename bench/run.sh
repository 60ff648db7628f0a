#!/usr/bin/env bash
# Runs every benchmark; each prints its ratios measured side by side in one run.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 bench/kraus_tables.py "$@"
/usr/bin/python3 bench/bauszat_tables.py
