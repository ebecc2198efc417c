#!/usr/bin/env bash
# Array width against throughput on the cluster this host submits to (docs/cluster.md "Measured"):
# one archive of generated videos, planned into N shards, submitted with --max-parallel K for each K,
# timed from `batch submit` to the last task leaving the queue.
# Usage: scripts/bench_slurm_width.sh NEOPIPE [VIDEOS] [SHARDS] [WIDTHS...]
#   defaults: 32 videos of 320x240, 100 frames; 8 shards; widths 1 2 4 8.
set -euo pipefail
neopipe=$(realpath "${1:?usage: bench_slurm_width.sh NEOPIPE [VIDEOS] [SHARDS] [WIDTHS...]}")
videos=${2:-32}
shards=${3:-8}
shift 3 2>/dev/null || shift $#
widths=("$@")
[ ${#widths[@]} -gt 0 ] || widths=(1 2 4 8)
timeout 5 scontrol ping >/dev/null || { echo "bench_slurm_width: no Slurm cluster answers" >&2; exit 1; }

work=$(mktemp -d /tmp/neopipe-slurm-width.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work"
mkdir videos
sources=(testsrc testsrc2 smptebars rgbtestsrc mandelbrot yuvtestsrc cellauto "life=seed=3")
for ((i = 0; i < videos; i++)); do
  src=${sources[$((i % ${#sources[@]}))]}
  case "$src" in *=*) spec="$src:size=320x240:rate=25" ;; *) spec="$src=size=320x240:rate=25" ;; esac
  ffmpeg -nostdin -loglevel error -f lavfi -i "$spec" -frames:v 100 -pix_fmt yuv420p -c:v mpeg4 -q:v 3 \
    -metadata comment="clip $i" "videos/v$(printf %03d "$i").mp4"
done
echo "$videos videos of 320x240 x 100 frames ($(du -sh videos | cut -f1)); $shards shards; node: $(sinfo -h -N -o '%c CPUs, %m MB' | head -1); load $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%6s %9s %11s %10s\n' WIDTH SECONDS FILES/HOUR FRAMES/S
for k in "${widths[@]}"; do
  rm -rf "out$k"
  "$neopipe" batch plan videos --out "out$k" --shards "$shards" --quiet >/dev/null
  start=$(date +%s.%N)
  job=$("$neopipe" batch submit --manifest "out$k/manifest.json" --max-parallel "$k" --cpus-per-task 1)
  deadline=$((SECONDS + 600))
  while [ -n "$(timeout 10 squeue -h -j "$job")" ]; do
    [ $SECONDS -lt $deadline ] || { scancel "$job"; echo "width $k: not done in 600 s" >&2; exit 1; }
    sleep 0.1
  done
  end=$(date +%s.%N)
  frames=$("$neopipe" batch merge --manifest "out$k/manifest.json" --out "out$k/all.csv" --json |
           sed 's/.*"frames":\([0-9]*\).*/\1/')
  awk -v k="$k" -v s="$start" -v e="$end" -v n="$videos" -v f="$frames" \
    'BEGIN { t = e - s; printf "%6d %9.2f %11.0f %10.0f\n", k, t, n / t * 3600, f / t }'
done
