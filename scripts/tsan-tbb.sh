#!/usr/bin/env bash
# Builds the installed oneTBB again, from Debian's own source package of the
# same version, with ThreadSanitizer, and prints the folder of its libtbb.so.
#
# Why: TBB hands a parallel_for's work to its threads and joins them inside
# libtbb.so. Debian's library is not instrumented, so ThreadSanitizer never
# sees that hand-over and reports every loop body as racing with the code
# around it (about 1,900 reports in the loader tests). With an instrumented
# libtbb.so first on LD_LIBRARY_PATH, the hand-over is seen and a report
# means a real race.
#
# Usage: scripts/tsan-tbb.sh DIR   (built once into DIR/tbb-VERSION/, then reused)
# Needs network access to the Debian archive (WEFT_DEBIAN_MIRROR, default
# https://deb.debian.org/debian), curl and dpkg-source (dpkg-dev). The .dsc
# comes over HTTPS; dpkg-source checks the files against its sizes and
# checksums (its signature too, where debian-keyring is installed).
set -euo pipefail
root="$1"
mirror="${WEFT_DEBIAN_MIRROR:-https://deb.debian.org/debian}"
fail() { echo "tsan-tbb: $*" >&2; exit 1; }

package=$(dpkg-query -W -f='${source:Package}' libtbb12 2>/dev/null) || fail "libtbb12 is not installed"
version=$(dpkg-query -W -f='${source:Version}' libtbb12)
upstream=${version%%-*}
out="$root/tbb-$version"
libdir="$out/lib"
if [ -f "$libdir/libtbb.so.12" ]; then
  echo "$libdir"
  exit 0
fi
command -v dpkg-source >/dev/null || fail "dpkg-source not found (apt-get install dpkg-dev)"
command -v curl >/dev/null || fail "curl not found (apt-get install curl)"

src="$out/source"
rm -rf "$out" && mkdir -p "$src"
pool="$mirror/pool/main/${package:0:1}/$package"
dsc="${package}_${version}.dsc"
echo "tsan-tbb: fetching $package $version from $pool" >&2
curl -fsSL -o "$src/$dsc" "$pool/$dsc" || fail "cannot fetch $pool/$dsc"
# The files the .dsc lists; dpkg-source checks their sizes and checksums.
for file in $(awk '/^Checksums-Sha256:/{on=1; next} /^[^ ]/{on=0} on{print $3}' "$src/$dsc"); do
  curl -fsSL -o "$src/$file" "$pool/$file" || fail "cannot fetch $pool/$file"
done
(cd "$src" && dpkg-source -x "$dsc" tree >"$out/unpack.log" 2>&1) ||
  fail "dpkg-source could not unpack $dsc (see $out/unpack.log)"

echo "tsan-tbb: building libtbb $upstream with -fsanitize=thread" >&2
CC=clang CXX=clang++ cmake -S "$src/tree" -B "$out/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBB_STRICT=OFF \
  -DTBBMALLOC_BUILD=OFF -DTBBMALLOC_PROXY_BUILD=OFF >"$out/configure.log" 2>&1 ||
  fail "configure failed (see $out/configure.log)"
cmake --build "$out/build" -j"${WEFT_JOBS:-$(nproc)}" --target tbb >"$out/build.log" 2>&1 ||
  fail "build failed (see $out/build.log)"
mkdir -p "$libdir"
cp -P "$out"/build/*/libtbb.so* "$libdir/"
[ -f "$libdir/libtbb.so.12" ] || fail "the build made no libtbb.so.12"
echo "$libdir"
