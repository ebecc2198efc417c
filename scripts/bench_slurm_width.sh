#!/usr/bin/env bash
# Array width against throughput on the cluster this host submits to (docs/cluster.md "Measured"):
# one archive of generated videos, planned into N shards, submitted with --max-parallel K for each K,
# timed from `batch submit` to the last task leaving the queue.
# Usage: scripts/bench_slurm_width.sh NEOPIPE [VIDEOS] [SHARDS] [WIDTHS...]
#   defaults: 32 videos of 320x240, 100 frames (BENCH_SIZE, BENCH_FRAMES); 8 shards; widths 1 2 4 8.
# The first row, "none", runs every shard one after the other in one process without Slurm: the
# processing alone. PROC S is the processing time the tasks report, summed (the rest is Slurm's).
set -euo pipefail
neopipe=$(realpath "${1:?usage: bench_slurm_width.sh NEOPIPE [VIDEOS] [SHARDS] [WIDTHS...]}")
videos=${2:-32}
shards=${3:-8}
shift 3 2>/dev/null || shift $#
widths=("$@")
size=${BENCH_SIZE:-320x240}
frames_per_video=${BENCH_FRAMES:-100}
[ ${#widths[@]} -gt 0 ] || widths=(1 2 4 8)
timeout 5 scontrol ping >/dev/null || { echo "bench_slurm_width: no Slurm cluster answers" >&2; exit 1; }

work=$(mktemp -d /tmp/neopipe-slurm-width.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work"
mkdir videos
sources=(testsrc testsrc2 smptebars rgbtestsrc mandelbrot yuvtestsrc cellauto "life=seed=3")
for ((i = 0; i < videos; i++)); do
  src=${sources[$((i % ${#sources[@]}))]}
  case "$src" in *=*) spec="$src:size=$size:rate=25" ;; *) spec="$src=size=$size:rate=25" ;; esac
  ffmpeg -nostdin -loglevel error -f lavfi -i "$spec" -frames:v "$frames_per_video" -pix_fmt yuv420p -c:v mpeg4 -q:v 3 \
    -metadata comment="clip $i" "videos/v$(printf %03d "$i").mp4"
done
echo "$videos videos of $size x $frames_per_video frames ($(du -sh videos | cut -f1)); $shards shards; node: $(sinfo -h -N -o '%c CPUs, %m MB' | head -1); load $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%6s %9s %11s %10s %7s\n' WIDTH SECONDS FILES/HOUR FRAMES/S "PROC S"
report() {  # width, start, end, out folder
  local summary frames proc
  summary=$("$neopipe" batch merge --manifest "$4/manifest.json" --out "$4/all.csv" --json)
  frames=$(sed 's/.*"frames":\([0-9]*\).*/\1/' <<<"$summary")
  proc=$(sed 's/.*"seconds":\([0-9.e+-]*\).*/\1/' <<<"$summary")
  awk -v k="$1" -v s="$2" -v e="$3" -v n="$videos" -v f="$frames" -v p="$proc" \
    'BEGIN { t = e - s; printf "%6s %9.2f %11.0f %10.0f %7.2f\n", k, t, n / t * 3600, f / t, p }'
}
"$neopipe" batch plan videos --out out0 --shards "$shards" --quiet >/dev/null
start=$(date +%s.%N)
for ((i = 0; i < shards; i++)); do "$neopipe" batch run --manifest out0/manifest.json --shard "$i" --threads 1 -q >/dev/null; done
report none "$start" "$(date +%s.%N)" out0
for k in "${widths[@]}"; do
  "$neopipe" batch plan videos --out "out$k" --shards "$shards" --quiet >/dev/null
  start=$(date +%s.%N)
  job=$("$neopipe" batch submit --manifest "out$k/manifest.json" --max-parallel "$k" --cpus-per-task 1)
  deadline=$((SECONDS + 600))
  while [ -n "$(timeout 10 squeue -h -j "$job")" ]; do
    [ $SECONDS -lt $deadline ] || { scancel "$job"; echo "width $k: not done in 600 s" >&2; exit 1; }
    sleep 0.1
  done
  report "$k" "$start" "$(date +%s.%N)" "out$k"
done
