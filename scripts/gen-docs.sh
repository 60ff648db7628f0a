#!/usr/bin/env bash
# Regenerates the generated part of every technique page, in place:
# docs/techniques/NAME.md holds, between the lines
#   <!-- BEGIN weft help NAME --markdown -->
#   <!-- END weft help NAME --markdown -->
# exactly what `weft help NAME --markdown` prints; everything outside them is
# written by hand. A registered technique without a page gets a new page with
# its title and the generated part; write its description above the markers.
# docs/usage.md holds `weft help options --markdown` and `weft help counters
# --markdown` the same way.
# tests/cli/docs_test.cpp fails when a page is out of date.
# Usage: scripts/gen-docs.sh [path/to/weft]   (default build/bin/weft)
set -euo pipefail
cd "$(dirname "$0")/.."
weft=${1:-build/bin/weft}
[ -x "$weft" ] || { echo "gen-docs: $weft not found; run scripts/build.sh first" >&2; exit 1; }
dir=docs/techniques
mkdir -p "$dir"
# External plugins are not documented here.
generated=$(mktemp)
trap 'rm -f "$generated" "$generated.page"' EXIT
names=$(env -u WEFT_PLUGIN_PATH "$weft" --list-plugins | awk '{print $1}')
# regen PAGE NAME: the part of PAGE between NAME's markers, from `weft help NAME --markdown`.
regen() {
  local page=$1 name=$2
  local begin="<!-- BEGIN weft help $name --markdown -->"
  local end="<!-- END weft help $name --markdown -->"
  env -u WEFT_PLUGIN_PATH "$weft" help "$name" --markdown > "$generated"
  if [ ! -f "$page" ]; then
    printf '# %s\n\n%s\n%s\n' "$name" "$begin" "$end" > "$page"
    echo "gen-docs: new page $page: describe the technique above the generated part"
  fi
  if [ "$(grep -cxF "$begin" "$page")" != 1 ] || [ "$(grep -cxF "$end" "$page")" != 1 ]; then
    echo "gen-docs: $page needs exactly one line '$begin' and one line '$end'" >&2
    exit 1
  fi
  awk -v begin="$begin" -v end="$end" -v gen="$generated" '
    $0 == end   { skip = 0 }
    !skip       { print }
    $0 == begin { while ((getline line < gen) > 0) print line; skip = 1 }
  ' "$page" > "$generated.page"
  if cmp -s "$generated.page" "$page"; then
    rm -f "$generated.page"
  else
    mv "$generated.page" "$page"
    echo "gen-docs: updated $page"
  fi
}
for name in $names; do regen "$dir/$name.md" "$name"; done
# The render option table and the counter list in docs/usage.md.
for name in options counters; do regen docs/usage.md "$name"; done
for page in "$dir"/*.md; do
  name=$(basename "$page" .md)
  grep -qxF "$name" <<< "$names" || echo "gen-docs: $page: no technique named $name is registered" >&2
done
