#!/usr/bin/env bash
# Installs the Debian packages neopipe needs to build, test and run (`--demo`: only to build and run;
# `--slurm`: only the one-node Slurm cluster of scripts/slurm-local.sh, for `neopipe batch`'s tests).
# Safe to run again: it installs only what is missing. Needs root, or sudo.
set -euo pipefail

# What building and running neopipe needs (scripts/demo.sh installs only these: `setup.sh --demo`) ...
packages=(
  build-essential cmake pkg-config
  libopencv-dev          # codecs, video I/O, reference implementations
  libeigen3-dev          # geometry (calibration, navigation)
  libtbb-dev             # oneTBB: the scheduler's threads
  libhwy-dev             # Highway: SIMD in the kernels
  libyaml-cpp-dev        # graph specs, worlds
  libcli11-dev           # the command line
  libfmt-dev
  nlohmann-json3-dev     # JSON output
  libavformat-dev libavcodec-dev libavutil-dev libswscale-dev  # FFmpeg's libraries: neopipe's video reader
  ccache                 # rebuilds (and the sanitizer trees of scripts/sanitize.sh) recompile only what changed
)
# ... and what testing, benchmarking and fuzzing it needs besides.
if [ "${1:-}" = "--slurm" ]; then
  packages=(slurm-wlm munge)  # slurmctld, slurmd, sbatch/squeue/sacct/scancel, and munged to authenticate
elif [ "${1:-}" != "--demo" ]; then
  packages+=(
    libgtest-dev libgmock-dev
    libbenchmark-dev       # kernel micro-benchmarks
    libhalide14-0-dev      # the Halide peer of `neopipe bench` (bench/halide/, AOT-compiled at build time)
    ffmpeg                 # the tests make sample videos with it
    opencv-doc             # sample data the tests check against (vtest.avi, the left01..14 chessboard photos)
    dpkg-dev               # dpkg-source: scripts/sanitizers/onetbb-tsan.sh unpacks Debian's oneTBB source
    clang libclang-rt-14-dev  # libFuzzer and the sanitizers' runtimes for clang (scripts/fuzz.sh)
    pybind11-dev python3-dev python3-numpy  # the Python module (python/)
    python3-pytest python3-opencv           # the Python module's tests (cv2 is the reference they compare with)
    python3-pandas python3-matplotlib       # optional for the module; examples/python uses them
  )
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages are installed"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo=sudo
fi
echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
