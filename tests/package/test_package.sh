#!/usr/bin/env bash
# The installed package, as a user meets it: installs the build tree into a fresh prefix, checks what
# is there (and what is not), runs the installed program (which must load the installed media
# plug-in), builds examples/consumer against the prefix with find_package(neopipe) and checks its
# blobs, checks that neopipe's own flags (-march=native, warnings) did not reach the consumer, and
# builds the same program again from the pkg-config file alone.
#   test_package.sh BUILD_DIR CONSUMER_SOURCE_DIR CXX [LAUNCHER]
set -euo pipefail
build=$1 consumer=$2 cxx=$3 launcher=${4:-}
work=$(mktemp -d "${TMPDIR:-/tmp}/neopipe-package.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
fail() { echo "FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" > "$work/install.log"
# lib/ or lib/<multiarch>/, as GNUInstallDirs chose for the build's prefix.
config=$(cd "$prefix" && find . -name neopipeConfig.cmake -path '*/cmake/neopipe/*' | head -n 1)
[ -n "$config" ] || fail "no neopipeConfig.cmake under $prefix"
libdir=$(dirname "$(dirname "$(dirname "${config#./}")")")

# What a user needs is installed; internal headers are not.
for f in bin/neopipe $libdir/neopipe/libneopipe_media.so $libdir/libneopipe_pipeline.a $libdir/libneopipe_rig.a \
  $libdir/cmake/neopipe/neopipeConfig.cmake $libdir/cmake/neopipe/neopipeConfigVersion.cmake \
  $libdir/cmake/neopipe/neopipeTargets.cmake $libdir/pkgconfig/neopipe.pc include/neopipe/neopipe_version.hpp \
  include/neopipe/pipeline/graph_spec.hpp include/neopipe/pipeline/inline_runner.hpp \
  include/neopipe/calib/calibration.hpp include/neopipe/sim/world.hpp include/neopipe/nav/mapmaker/planner.hpp \
  include/neopipe/rig/trials.hpp; do
  [ -e "$prefix/$f" ] || fail "not installed: $f"
done
for f in kernels/simd.hpp pipeline/io/libav_handles.hpp pipeline/media/media_backend.hpp pipeline/fusion.hpp; do
  [ ! -e "$prefix/include/neopipe/$f" ] || fail "internal header installed: $f"
done
! find "$prefix" -name '*_tests' -o -name '*bench*' | grep -q . || fail "tests or benchmarks installed"

# The installed program reports the package's version and loads the installed plug-in (the first
# image it writes needs it), not the build tree's.
version=$(sed -n 's/^Version: //p' "$prefix/$libdir/pkgconfig/neopipe.pc")
[ "$("$prefix/bin/neopipe" --version)" = "neopipe $version" ] || fail "neopipe --version is not neopipe $version"
"$prefix/bin/neopipe" sim world --objects 5 --seed 1 --out "$work/world.yaml" > /dev/null
LD_DEBUG=files "$prefix/bin/neopipe" sim render --world "$work/world.yaml" --realism ideal --out "$work/global.png" \
  > /dev/null 2> "$work/ld.log"
[ -s "$work/global.png" ] || fail "the installed program wrote no image"
grep -q "file=$prefix/$libdir/neopipe/libneopipe_media.so" "$work/ld.log" ||
  fail "the installed program did not load the installed plug-in: $(grep -o 'file=[^ ]*media[^ ]*' "$work/ld.log" || true)"

# A program elsewhere (neither beside the plug-in nor in bin/ of the prefix) loads the one
# NEOPIPE_MEDIA_PLUGIN names, before the build tree's.
mkdir "$work/elsewhere" && cp "$prefix/bin/neopipe" "$work/elsewhere/"
NEOPIPE_MEDIA_PLUGIN="$prefix/$libdir/neopipe/libneopipe_media.so" LD_DEBUG=files "$work/elsewhere/neopipe" sim render \
  --world "$work/world.yaml" --realism ideal --out "$work/elsewhere.png" > /dev/null 2> "$work/ld.log"
grep -q "file=$prefix/$libdir/neopipe/libneopipe_media.so" "$work/ld.log" ||
  fail "NEOPIPE_MEDIA_PLUGIN was not the plug-in loaded: $(grep -o 'file=[^ ]*media[^ ]*' "$work/ld.log" || true)"

# The consumer, through find_package.
cmake -S "$consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON ${launcher:+-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher"} \
  > "$work/configure.log" || { cat "$work/configure.log"; fail "the consumer does not configure"; }
cmake --build "$work/consumer" -j 2 > "$work/build.log" 2>&1 || { cat "$work/build.log"; fail "the consumer does not build"; }
! grep -E 'warning:' "$work/build.log" || fail "the consumer's build warns"
for flag in -march=native -Wshadow HWY_COMPILE_ONLY_STATIC; do
  ! grep -q -- "$flag" "$work/consumer/compile_commands.json" || fail "$flag leaked into the consumer's compile lines"
done
"$work/consumer/all_headers" > /dev/null || fail "all_headers failed"
# The composition table is compiled into the installed qrm library: no data file to find.
[ "$("$work/consumer/all_headers" qrm -)" = "$(printf '2214 triples\nneopipe %s: every installed header compiles' "$version")" ] ||
  fail "the installed qrm library does not give its composition table"

# Its blobs: three discs of radius 12 at (60,50), (200,120), (120,190), in raster order of their first
# pixel, the same from the owned cv::Mat (frame 0) and the strided buffer (frame 1).
check_blobs() {
  awk -v what="$1" '
    NR == 1 { if ($0 !~ /^neopipe [0-9]+\.[0-9]+\.[0-9]+$/) { print what ": no version line: " $0; exit 1 } next }
    { n[$1]++; key = $1 " " $2
      split("60 200 120", ex); split("50 120 190", ey)
      i = $2 + 1
      if ($4 - ex[i] > 0.01 || ex[i] - $4 > 0.01 || $5 - ey[i] > 0.01 || ey[i] - $5 > 0.01) {
        print what ": blob " key " at " $4 "," $5 ", expected " ex[i] "," ey[i]; bad = 1 }
      if (area == "") area = $3; else if ($3 != area) { print what ": areas differ: " $3 " vs " area; bad = 1 } }
    END { if (n[0] != 3 || n[1] != 3) { print what ": expected 3 blobs in each of frames 0 and 1"; bad = 1 }
          exit bad }' "$2"
}
"$work/consumer/blob_consumer" > "$work/cmake.out" || fail "blob_consumer failed"
check_blobs "find_package build" "$work/cmake.out" || { cat "$work/cmake.out"; fail "wrong blobs"; }

# The same program from the pkg-config file alone.
export PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig"
pkg-config --exists --print-errors neopipe || fail "pkg-config does not find neopipe"
[ "$(pkg-config --modversion neopipe)" = "$version" ] || fail "pkg-config version differs"
# shellcheck disable=SC2046  # pkg-config's words are separate arguments
$cxx -std=c++20 -O1 "$consumer/blob_consumer.cpp" -o "$work/pc_consumer" $(pkg-config --cflags --libs neopipe) \
  2> "$work/pc.log" || { cat "$work/pc.log"; fail "the consumer does not build with pkg-config's flags"; }
"$work/pc_consumer" > "$work/pc.out" || fail "the pkg-config build failed to run"
cmp -s "$work/cmake.out" "$work/pc.out" || fail "the pkg-config build prints other blobs"
echo "package OK: installed into a fresh prefix; find_package and pkg-config consumers print the expected blobs"
cat "$work/cmake.out"
