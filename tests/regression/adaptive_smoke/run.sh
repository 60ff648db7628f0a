#!/usr/bin/env bash
# Renders the small smoke with volume.adaptive3d and volume.preint and compares
# with the committed references; --update replaces them (review first).
set -euo pipefail
# References live in git: written with zip, the smallest lossless EXR
# compression (weft's default, rle, is the quickest to write).
here="$(cd "$(dirname "$0")" && pwd)"
root="$here/../../.."
weft="$root/build/bin/weft"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$weft" render "$root/data/smoke_small.vdb" --res 96x96 --technique volume.adaptive3d --set oracle=gradient_alpha --compression zip -o "$out/adaptive3d_gradient_alpha.exr"
"$weft" render "$root/data/smoke_small.vdb" --res 96x96 --technique volume.preint --compression zip -o "$out/preint.exr"
for f in adaptive3d_gradient_alpha.exr preint.exr; do
  if [ "${1:-}" = "--update" ]; then cp "$out/$f" "$here/ref/$f"; echo "updated ref/$f"
  else "$weft" diff "$out/$f" "$here/ref/$f" --fail 0.004; fi
done
