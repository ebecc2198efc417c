#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) in ./build-fuzz with clang and runs each for SECONDS (default
# 60) on a working copy of its seed corpus. Exits non-zero if any target crashed, leaked, took more
# than 2 s on one input or more than 1 GiB of memory; the input that did it is in build-fuzz/crashes/.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]     e.g. scripts/fuzz.sh 300 world custom_map
#
# Targets: graph_spec world calibration moves_csv points_csv blob_table custom_map image_signature
# video. JOBS sets the build's parallelism (default: the number of cores). docs/reliability.md says
# how to replay a crash and what the runs found.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=${1:-60}
[[ $seconds =~ ^[0-9]+$ ]] || { echo "usage: scripts/fuzz.sh [SECONDS] [TARGET...]" >&2; exit 2; }
shift $(($# > 0 ? 1 : 0))
all=(graph_spec world calibration moves_csv points_csv blob_table custom_map image_signature video)
if (($# > 0)); then targets=("$@"); else targets=("${all[@]}"); fi
for t in "${targets[@]}"; do
  [[ " ${all[*]} " == *" $t "* ]] || { echo "unknown fuzz target '$t' (known: ${all[*]})" >&2; exit 2; }
done

build=$root/build-fuzz
launcher=()
if command -v ccache >/dev/null; then
  # Paths relative to the checkout, so that another checkout of the same code hits the same cache.
  export CCACHE_BASEDIR=$root
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# Debug keeps assertions on; -O1 is what libFuzzer's documentation recommends: fast, still debuggable.
mkdir -p "$build"
cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DNEOPIPE_FUZZ=ON -DNEOPIPE_BUILD_TESTING=OFF -DNEOPIPE_BUILD_BENCHMARKS=OFF "${launcher[@]}" >"$build/configure.log" ||
  { cat "$build/configure.log" >&2; exit 1; }
cmake --build "$build" -j "${JOBS:-$(nproc)}" --target "${targets[@]/#/fuzz_}"

# The video reader's seeds are made here rather than checked in: tiny clips (16x16, 3 frames) in the
# containers and codecs neopipe meets, one turned by a display matrix, gray and RGB ones for the
# converter's other paths. Clips an encoder cannot make here are skipped.
make_video_seeds() {
  local dir=$1
  command -v ffmpeg >/dev/null || { echo "ffmpeg not found: the video target starts from an empty corpus" >&2; return; }
  local src=(-f lavfi -i testsrc2=size=16x16:rate=3 -frames:v 3 -an -map_metadata -1 -fflags +bitexact)
  local -A clips=(
    [h264.mp4]="-c:v libx264 -pix_fmt yuv420p -preset ultrafast"
    [mjpeg.avi]="-c:v mjpeg -pix_fmt yuvj420p"
    [ffv1.mkv]="-c:v ffv1"
    [ffv1_gray.mkv]="-c:v ffv1 -pix_fmt gray"
    [ffv1_bgr.mkv]="-c:v ffv1 -pix_fmt bgr0"
    [vp8.webm]="-c:v libvpx -b:v 100k"
    [mpeg4.mp4]="-c:v mpeg4"
    [png.mov]="-c:v png -pix_fmt rgb24"
    [h264.264]="-c:v libx264 -pix_fmt yuv420p -preset ultrafast -f h264"
  )
  local name
  for name in "${!clips[@]}"; do
    [[ -s $dir/$name ]] && continue
    # shellcheck disable=SC2086  # the options are words on purpose
    ffmpeg -nostdin -loglevel error -y "${src[@]}" ${clips[$name]} "$dir/$name" 2>/dev/null || rm -f "$dir/$name"
  done
  # FFmpeg 5.1 writes a display matrix for "rotate" only when it copies the stream.
  if [[ -s $dir/mpeg4.mp4 && ! -s $dir/mpeg4_turned.mp4 ]]; then
    ffmpeg -nostdin -loglevel error -y -i "$dir/mpeg4.mp4" -c copy -metadata:s:v:0 rotate=90 "$dir/mpeg4_turned.mp4" \
      2>/dev/null || rm -f "$dir/mpeg4_turned.mp4"
  fi
}

dict_of() {
  case $1 in
    moves_csv | points_csv | blob_table) echo "$root/fuzz/dict/csv.dict" ;;
    image_signature | video) ;;
    *) echo "$root/fuzz/dict/$1.dict" ;;
  esac
}

# From a run's log: a field of libFuzzer's last status line ("#N DONE cov: C ft: F corp: K/..."), or
# one of its final stats (-print_final_stats=1).
status_field() { grep -E '^#[0-9]+[[:space:]].*cov: ' "$2" | tail -n 1 | sed -nE "s/.* $1: ([0-9]+).*/\1/p"; }
final_stat() { sed -nE "s/^stat::$1: *([0-9]+).*/\1/p" "$2" | tail -n 1; }

mkdir -p "$build/crashes" "$build/logs"
failed=()
printf '%-16s %6s %10s %12s %7s %7s %7s  %s\n' target seconds runs execs/s cov ft corpus result
for t in "${targets[@]}"; do
  corpus=$build/corpus/$t
  mkdir -p "$corpus"
  # A working copy: what libFuzzer adds stays under build-fuzz, and the checked-in seeds stay few.
  if compgen -G "fuzz/corpus/$t/*" >/dev/null; then cp -n fuzz/corpus/"$t"/* "$corpus"/; fi
  [[ $t == video ]] && make_video_seeds "$corpus"
  args=(-max_total_time="$seconds" -timeout=2 -rss_limit_mb=1024 -print_final_stats=1
    -artifact_prefix="$build/crashes/$t-")
  dict=$(dict_of "$t")
  [[ -n $dict ]] && args+=(-dict="$dict")
  log=$build/logs/$t.log
  status=0
  "$build/fuzz/fuzz_$t" "${args[@]}" "$corpus" </dev/null >"$log" 2>&1 || status=$?
  result=ok
  if ((status != 0)); then
    result="FAILED (exit $status; see $log, $build/crashes/$t-*)"
    failed+=("$t")
  fi
  printf '%-16s %6s %10s %12s %7s %7s %7s  %s\n' "$t" "$seconds" "$(final_stat number_of_executed_units "$log")" \
    "$(final_stat average_exec_per_sec "$log")" "$(status_field cov "$log")" "$(status_field ft "$log")" \
    "$(status_field corp "$log")" "$result"
done

if ((${#failed[@]} > 0)); then
  echo "fuzzing found problems in: ${failed[*]}" >&2
  exit 1
fi
