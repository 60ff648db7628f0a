#!/usr/bin/env bash
# Regenerates docs/sampling.md's pattern images (docs/images/periodograms*.png,
# zoneplate_strip.png, motion_blur_strip.png) and docs/sampling_report.csv with build/bin/weft and
# oiiotool. Usage: scripts/pattern_images.sh [--threads N]
set -euo pipefail
cd "$(dirname "$0")/.."
threads=2
[ "${1:-}" = "--threads" ] && threads="$2"
weft=build/bin/weft
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for p in regular jittered random poisson point_diffusion lloyd hammersley lp; do
  "$weft" pattern "$p" --count 256 --seeds 32 --freq 64 -o "$tmp/$p.exr" --preview "$tmp/$p.png" > /dev/null
done
oiiotool "$tmp"/{regular,jittered,random,poisson,point_diffusion,lloyd,hammersley,lp}.png --mosaic:pad=6 4x2 -o docs/images/periodograms.png

"$weft" pattern jittered --count 16 --tile 4x4 --seeds 32 --freq 64 -o "$tmp/dep.exr" --preview "$tmp/dep.png" > /dev/null
"$weft" pattern interleaved:4x4,basis=jittered --count 16 --seeds 32 --freq 64 -o "$tmp/ij.exr" --preview "$tmp/ij.png" > /dev/null
"$weft" pattern interleaved:4x4,basis=lloyd --count 16 --seeds 32 --freq 64 -o "$tmp/il.exr" --preview "$tmp/il.png" > /dev/null
oiiotool "$tmp"/{dep,ij,il}.png --mosaic:pad=6 3x1 -o docs/images/periodograms_tiles.png

i=0
for p in regular jittered none interleaved:4x4,basis=jittered interleaved:4x4,basis=lloyd; do
  i=$((i + 1))
  set_pattern=()
  [ "$p" != none ] && set_pattern=(--set "pattern=$p")
  "$weft" render builtin:zoneplate --res 128x128 --spp 4 "${set_pattern[@]}" --threads "$threads" -o "$tmp/z$i.exr" --preview "$tmp/z$i.png"
done
"$weft" render builtin:zoneplate --res 128x128 --set reference=true --threads "$threads" -o "$tmp/z6.exr" --preview "$tmp/z6.png"
oiiotool "$tmp"/z{1,2,3,4,5,6}.png --mosaic:pad=4 6x1 -o docs/images/zoneplate_strip.png

i=0
for p in regular none interleaved:4x4,basis=jittered; do
  i=$((i + 1))
  set_pattern=()
  [ "$p" != none ] && set_pattern=(--set "pattern=$p")
  "$weft" render builtin:disc --res 128x128 --spp 4 "${set_pattern[@]}" --threads "$threads" -o "$tmp/d$i.exr" --preview "$tmp/d$i.png"
done
"$weft" render builtin:disc --res 128x128 --set reference=true --threads "$threads" -o "$tmp/d4.exr" --preview "$tmp/d4.png"
oiiotool "$tmp"/d{1,2,3,4}.png --mosaic:pad=4 4x1 -o docs/images/motion_blur_strip.png

"$weft" sampling-report --threads "$threads" -o docs/sampling_report.csv
