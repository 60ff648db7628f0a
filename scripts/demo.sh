#!/usr/bin/env bash
# Installs dependencies, builds, and renders the built-in default scene to
# out/demo.exr (scene-linear, with metadata) and out/demo.png (sRGB preview).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
mkdir -p out
build/bin/weft render builtin:cloud --res 512x512 -o out/demo.exr --preview out/demo.png --stats out/demo.json -v
echo "demo: wrote out/demo.exr, out/demo.png and out/demo.json"
