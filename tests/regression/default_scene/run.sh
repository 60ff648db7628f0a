#!/usr/bin/env bash
# Renders the default scene and compares it with the committed reference;
# --update replaces the reference (review the new picture before committing).
set -euo pipefail
# References live in git: written with zip, the smallest lossless EXR
# compression (weft's default, rle, is the quickest to write).
here="$(cd "$(dirname "$0")" && pwd)"
weft="$here/../../../build/bin/weft"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$weft" render builtin:cloud --res 128x128 --compression zip -o "$out/cloud_128.exr"
if [ "${1:-}" = "--update" ]; then
  cp "$out/cloud_128.exr" "$here/ref/cloud_128.exr"
  echo "updated $here/ref/cloud_128.exr"
else
  "$weft" diff "$out/cloud_128.exr" "$here/ref/cloud_128.exr" --fail 0.004
fi
