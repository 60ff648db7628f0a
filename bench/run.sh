#!/usr/bin/env bash
# Runs every benchmark; each prints its ratios measured side by side in one
# run, and the headline ones (benchlib.headline) end up in one table.
set -euo pipefail
cd "$(dirname "$0")/.."
export WEFT_BENCH_HEADLINES
WEFT_BENCH_HEADLINES="$(mktemp "${TMPDIR:-/tmp}/weft-headlines.XXXXXX")"
trap 'rm -f "$WEFT_BENCH_HEADLINES"' EXIT
build/bin/weft_bench_patterns --threads 2
build/bin/hwsim_throughput
python3 bench/kraus_tables.py "$@"
/usr/bin/python3 bench/volume_vs_vdb_render.py "$@"
/usr/bin/python3 bench/volume_vs_vtk.py
/usr/bin/python3 bench/segovia_tables.py
/usr/bin/python3 bench/bauszat_tables.py
/usr/bin/python3 bench/sweep_overhead.py
/usr/bin/python3 bench/exr_write.py
/usr/bin/python3 bench/thread_scaling.py
/usr/bin/python3 bench/python_threads.py
/usr/bin/python3 bench/emission_cost.py
/usr/bin/python3 bench/scene_load.py
/usr/bin/python3 bench/cancel_latency.py
/usr/bin/python3 bench/headlines.py "$WEFT_BENCH_HEADLINES"
