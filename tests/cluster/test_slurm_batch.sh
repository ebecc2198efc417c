#!/usr/bin/env bash
# `neopipe batch` on a real Slurm cluster (scripts/slurm-local.sh start, or any cluster this host can
# submit to): array jobs over generated videos, a shard cancelled mid-way and resubmitted, a corrupt
# input, and sharded nav trials. Usage: tests/cluster/test_slurm_batch.sh NEOPIPE [WORK_DIR]
# Exits 77 (CTest's "skipped") when no Slurm answers here. Every wait is bounded.
#
# The work folder must be visible at the same path on the nodes that run the jobs (on the local
# one-node cluster, any folder is).
set -euo pipefail

neopipe=$(realpath "${1:?usage: test_slurm_batch.sh NEOPIPE [WORK_DIR]}")
work=${2:-}
job_timeout=${NEOPIPE_SLURM_TEST_TIMEOUT:-120}  # seconds an array job may take before the test fails

if ! command -v sbatch >/dev/null || ! timeout 5 sinfo -h >/dev/null 2>&1 || ! timeout 5 scontrol ping >/dev/null 2>&1; then
  echo "test_slurm_batch: SKIPPED: no Slurm cluster answers here (scripts/slurm-local.sh start)"
  exit 77
fi
command -v ffmpeg >/dev/null || { echo "test_slurm_batch: ffmpeg is needed to make the test videos" >&2; exit 1; }

if [ -z "$work" ]; then
  work=$(mktemp -d /tmp/neopipe-slurm-test.XXXXXX)
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work"
cd "$work"

failures=0
pass() { echo "PASS: $*"; }
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
die() { echo "FAIL: $*" >&2; exit 1; }

# Waits until job $1 has left the queue; fails the test after $job_timeout seconds.
wait_job() {
  local job=$1 deadline=$((SECONDS + job_timeout))
  while [ -n "$(timeout 10 squeue -h -j "$job" 2>/dev/null)" ]; do
    if [ $SECONDS -ge $deadline ]; then
      timeout 10 squeue -j "$job" >&2 || true
      timeout 10 scancel "$job" || true
      die "job $job still queued or running after ${job_timeout} s"
    fi
    sleep 0.3
  done
}

# --- Inputs: small videos from ffmpeg's test sources (deterministic), one corrupt file. -------------
mkdir -p videos
i=0
for src in testsrc testsrc2 smptebars rgbtestsrc "mandelbrot=size=160x120" "life=size=160x120:seed=3" \
           "cellauto=size=160x120:seed=5" "testsrc=size=200x150"; do
  case "$src" in *size=*) spec="$src:rate=25" ;; *) spec="$src=size=160x120:rate=25" ;; esac
  ffmpeg -nostdin -loglevel error -f lavfi -i "$spec" -frames:v 40 -pix_fmt yuv420p -c:v mpeg4 -q:v 3 \
    "videos/clip$i.mp4"
  i=$((i + 1))
done
printf 'not a video: a corrupt input must fail alone\n' > videos/corrupt.mp4
total_inputs=$((i + 1))

# The reference: `neopipe run` on each good file, with an input column, in manifest (path) order.
expected_table() {  # folder
  local first=1
  for v in $(find "$work/$1" -name '*.mp4' | LC_ALL=C sort); do
    [ "$(basename "$v")" = corrupt.mp4 ] && continue
    "$neopipe" run "$v" --quiet > run.csv || die "neopipe run $v failed"
    if [ $first = 1 ]; then sed -n '1s/^/input,/p' run.csv; first=0; fi
    tail -n +2 run.csv | sed "s|^|$v,|"
  done
}
expected_table videos > expected.csv

# --- 1. An array job over the archive: merged table = `neopipe run` on each file. -------------------
"$neopipe" batch plan videos --out out1 --shards 3 --quiet
manifest=$work/out1/manifest.json
job=$("$neopipe" batch submit --manifest "$manifest" --max-parallel 2)
[[ "$job" =~ ^[0-9]+$ ]] || die "batch submit printed '$job', not a job id"
wait_job "$job"
"$neopipe" batch status --manifest "$manifest" --json > status1.json
"$neopipe" batch merge --manifest "$manifest" --out merged1.csv --json > summary1.json
if cmp -s merged1.csv expected.csv; then pass "array job: merged table equals neopipe run on each file"
else fail "array job: merged table differs from neopipe run on each file (diff $work/merged1.csv $work/expected.csv)"; fi

# --- 2. The corrupt input is recorded as failed, with its error line; the others succeed. ----------
if grep -q '"done":'$((total_inputs - 1)) status1.json && grep -q '"failed":1' status1.json &&
   grep -q '"pending":0' status1.json; then pass "status: $((total_inputs - 1)) done, 1 failed, 0 pending"
else fail "status after the job: $(cat status1.json)"; fi
if grep -q 'corrupt.mp4' summary1.json && grep -q '"error":"[^"]' summary1.json; then
  pass "merge summary lists the corrupt input with its error line"
else fail "merge summary: $(cat summary1.json)"; fi

# --- 3. A shard cancelled mid-way, resubmitted: only unfinished inputs rerun, same merge. ----------
# One shard holds every input: eight larger videos (a quarter of a second each), so cancelling it
# after its first input leaves most undone.
mkdir -p videos2
i=0
for src in testsrc testsrc2 smptebars rgbtestsrc mandelbrot "life=seed=3:size=640x480" cellauto yuvtestsrc; do
  case "$src" in *size=*) spec="$src:rate=25" ;; *=*) spec="$src:size=640x480:rate=25" ;; *) spec="$src=size=640x480:rate=25" ;; esac
  ffmpeg -nostdin -loglevel error -f lavfi -i "$spec" -frames:v 120 -pix_fmt yuv420p -c:v mpeg4 -q:v 3 \
    "videos2/long$i.mp4"
  i=$((i + 1))
done
expected_table videos2 > expected2.csv
"$neopipe" batch plan videos2 --out out2 --shards 1 --quiet
manifest2=$work/out2/manifest.json
job=$("$neopipe" batch submit --manifest "$manifest2")
deadline=$((SECONDS + job_timeout))
until compgen -G "out2/done/*.json" >/dev/null; do
  [ $SECONDS -lt $deadline ] || die "no input done ${job_timeout} s after submitting job $job"
  sleep 0.02
done
timeout 10 scancel "$job"
wait_job "$job"
done_before=$(compgen -G 'out2/done/*.json' | wc -l)
inputs2=$(find videos2 -name '*.mp4' | wc -l)
if [ "$done_before" -ge "$inputs2" ]; then
  fail "cancel: the shard finished ($done_before done) before scancel; nothing left to resume (slow the inputs down)"
else
  pass "cancel: $done_before of $inputs2 inputs done when the shard was cancelled"
fi
# The done inputs' markers and tables, by inode and modification time (ns): a rerun replaces a file
# by a rename, so a rerun input would show a new inode.
done_keys=$(compgen -G 'out2/done/*.json' | xargs -n1 basename | sed 's/\.json$//')
stamp() { for k in $done_keys; do stat -c '%n %i %y' "out2/done/$k.json" "out2/tables/$k.csv"; done; }
before=$(stamp)
job=$("$neopipe" batch submit --manifest "$manifest2")
wait_job "$job"
after=$(stamp)
if [ "$before" = "$after" ]; then pass "resubmit: the $done_before inputs done before were not rerun"
else fail "resubmit: inputs done before the cancel were rewritten"; fi
"$neopipe" batch merge --manifest "$manifest2" --out merged2.csv > /dev/null
if cmp -s merged2.csv expected2.csv; then pass "resubmit: merged table still equals neopipe run on each file"
else fail "resubmit: merged table differs (diff $work/merged2.csv $work/expected2.csv)"; fi

# --- 4. Sharded nav trials on the cluster, merged = the unsharded run (wall time left out). ---------
"$neopipe" sim world --objects 60 --seed 3 --out world.yaml > /dev/null
nav_args=(nav --world "$work/world.yaml" --trials 6 --seed 5 --sigma-map 0.5 --json --threads 1)
"$neopipe" "${nav_args[@]}" > nav_whole.json
mkdir -p nav_shards
cat > nav.sbatch <<SCRIPT
#!/bin/bash
#SBATCH --array=0-2
#SBATCH --output=$work/nav_shards/%a.log
exec "$neopipe" ${nav_args[*]} --shard "\$SLURM_ARRAY_TASK_ID/3" > "$work/nav_shards/\$SLURM_ARRAY_TASK_ID.json"
SCRIPT
job=$(timeout 30 sbatch --parsable nav.sbatch)
wait_job "$job"
"$neopipe" batch merge-shards nav_shards/2.json nav_shards/0.json nav_shards/1.json --out nav_merged.json
# The merge is the unsharded JSON without its two wall-time fields (rig/trials_shards.hpp).
sed -e 's/"frames_per_second":[^,]*,//' -e 's/"seconds":[^,]*,//' nav_whole.json > nav_whole_untimed.json
if cmp -s nav_merged.json nav_whole_untimed.json; then pass "nav: 3 shards on Slurm merge byte-identical to the unsharded trials"
else fail "nav: merged shards differ from the unsharded run (diff $work/nav_merged.json $work/nav_whole_untimed.json)"; fi

if [ $failures -ne 0 ]; then
  echo "test_slurm_batch: $failures failed (work folder $work)" >&2
  trap - EXIT
  exit 1
fi
echo "test_slurm_batch: all passed"
