#!/usr/bin/env bash
# Renders every case under tests/regression/combined/ (each a folder with
# case.json and ref.exr) and judges it by the rule in its case.json, as the
# test suite does; --update replaces the references (review them first).
set -euo pipefail
# References live in git: written with zip, the smallest lossless EXR
# compression (weft's default, rle, is the quickest to write).
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
weft="$root/build/bin/weft"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
failed=0
for case in "$here"/*/case.json; do
  dir="$(dirname "$case")"
  name="$(basename "$dir")"
  mapfile -t args < <(/usr/bin/python3 -c '
import json, sys
c = json.load(open(sys.argv[1]))
print(sys.argv[2] + "/" + c["input"]); print("--technique"); print(c["technique"])
print("--res"); print(c["resolution"]); print("--spp"); print(c.get("spp", 1))
for s in c.get("set", []): print("--set"); print(s)' "$case" "$root")
  "$weft" render "${args[@]}" --compression zip -o "$out/$name.exr"
  if [ "${1:-}" = "--update" ]; then
    cp "$out/$name.exr" "$dir/ref.exr"; echo "updated $name/ref.exr"
  elif ! "$weft" diff "$out/$name.exr" "$dir/ref.exr" --rule "$case"; then
    failed=1
  fi
done
exit $failed
