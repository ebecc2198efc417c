#!/usr/bin/env bash
# Builds oneTBB with -fsanitize=thread into PREFIX (scripts/sanitize.sh thread uses it).
#
#   scripts/sanitizers/onetbb-tsan.sh PREFIX
#
# Debian's libtbb is not built with TSan: every hand-over through a TBB task (an image written by one
# thread, read by the worker the task runs on) looks like a race. So the thread tree links this copy,
# built from Debian's source package of exactly the installed libtbb-dev, so headers and library
# agree. Only the library (no tests, no tbbmalloc: neopipe does not use it); about 30 s on 2 cores.
# Skips the build when PREFIX already holds the same version. Fetching the source needs Debian's
# deb-src entries: when they are missing, they are added (a copy of the deb entries, as root or
# through sudo) and the package lists updated.
set -euo pipefail
prefix=${1:?usage: scripts/sanitizers/onetbb-tsan.sh PREFIX}
version=$(dpkg-query -W -f='${source:Version}' libtbb-dev 2>/dev/null) ||
  { echo "onetbb-tsan: libtbb-dev is not installed (run scripts/setup.sh)" >&2; exit 1; }
stamp="onetbb $version, $(c++ --version | head -n 1), -fsanitize=thread"
if [[ -s $prefix/lib/libtbb.so.12 && -f $prefix/stamp && $(cat "$prefix/stamp") == "$stamp" ]]; then
  echo "onetbb-tsan: $prefix has $stamp"
  exit 0
fi

as_root() {
  if [[ $(id -u) -eq 0 ]]; then "$@"; else sudo "$@"; fi
}
if ! apt-get source --print-uris "onetbb=$version" >/dev/null 2>&1; then
  echo "onetbb-tsan: adding deb-src entries for Debian's archive (/etc/apt/sources.list.d/neopipe-deb-src.*)"
  for f in /etc/apt/sources.list.d/*.sources; do
    [[ -f $f ]] || continue
    sed -n 's/^Types:.*\bdeb\b.*/Types: deb-src/;p' "$f" | as_root tee "/etc/apt/sources.list.d/neopipe-deb-src-$(basename "$f")" >/dev/null
  done
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [[ -f $f ]] || continue
    sed -n 's/^deb /deb-src /p' "$f" | as_root tee "/etc/apt/sources.list.d/neopipe-deb-src-$(basename "$f")" >/dev/null
  done
  as_root apt-get update -qq
fi

# A fixed folder beside PREFIX (not a random one), so that ccache finds the same paths next time.
work=$prefix.work
rm -rf "$work"
mkdir -p "$work"
trap 'rm -rf "$work"' EXIT
(cd "$work" && apt-get source --download-only -qq "onetbb=$version" 2>/dev/null &&
  dpkg-source -x ./*.dsc src >unpack.log 2>&1) ||
  { echo "onetbb-tsan: could not fetch or unpack Debian's onetbb $version source" >&2; exit 1; }
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$work/src" -B "$work/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_STRICT=OFF -DTBBMALLOC_BUILD=OFF -DCMAKE_INSTALL_PREFIX="$prefix" \
  -DCMAKE_INSTALL_LIBDIR=lib "${launcher[@]}" >"$work/configure.log" 2>&1 || { cat "$work/configure.log" >&2; exit 1; }
cmake --build "$work/build" -j "$(nproc)" >"$work/build.log" 2>&1 || { tail -n 30 "$work/build.log" >&2; exit 1; }
rm -rf "$prefix"
cmake --install "$work/build" >/dev/null
echo "$stamp" >"$prefix/stamp"
echo "onetbb-tsan: built $stamp in $prefix"
