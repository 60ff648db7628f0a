#!/usr/bin/env bash
# Installs dependencies, builds the weft executable and its modules (not the
# tests: scripts/test.sh builds those), and renders the default combined
# scene to out/demo.exr (scene-linear, with metadata) and out/demo.png (sRGB
# preview).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh weft
mkdir -p out
# Smoke inside the Cornell box: a volume and meshes in one scene, from files in the clone.
build/bin/weft render scenes/combined/smoke_in_cornell.json --res 512x512 --spp 16 -o out/demo.exr --preview out/demo.png --stats out/demo.json -v
echo "demo: wrote out/demo.exr, out/demo.png and out/demo.json"
