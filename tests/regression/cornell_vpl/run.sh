#!/usr/bin/env bash
# Renders the small Cornell box with lighting.vpl_deferred (4x4 interleaving,
# filtered) and compares it with the committed reference; --update replaces
# the reference (review the new picture before committing).
set -euo pipefail
# References live in git: written with zip, the smallest lossless EXR
# compression (weft's default, rle, is the quickest to write).
here="$(cd "$(dirname "$0")" && pwd)"
weft="$here/../../../build/bin/weft"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$weft" render "$here/../../../scenes/cornell.json" --technique lighting.vpl_deferred --res 64x64 --compression zip -o "$out/cornell_vpl_64.exr"
if [ "${1:-}" = "--update" ]; then
  cp "$out/cornell_vpl_64.exr" "$here/ref/cornell_vpl_64.exr"
  echo "updated $here/ref/cornell_vpl_64.exr"
else
  "$weft" diff "$out/cornell_vpl_64.exr" "$here/ref/cornell_vpl_64.exr" --fail 0.004
fi
