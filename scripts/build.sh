#!/usr/bin/env bash
# Configures and builds neopipe (Release) in ./build. `--target T` (repeatable) builds only T and what
# it needs (scripts/demo.sh: the program, its plug-in, the demo video), else everything; the other
# arguments go to CMake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=()
configure_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --target) targets+=(--target "$2"); shift 2 ;;
    *) configure_args+=("$1"); shift ;;
  esac
done
launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="$PWD"  # build trees in other folders share the cache
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "${configure_args[@]}"
cmake --build build -j "$(nproc)" "${targets[@]}"
