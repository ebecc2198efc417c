#!/usr/bin/env bash
# The README's first command: set up, build, and run neopipe on the demo video the build generates
# (24 marbles rolling over an unevenly lit table, 640x480, 120 frames).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh --demo
# Only what the demo runs: the `neopipe` program, its media plug-in (built with the pipeline) and the
# demo video (the demo_video target runs make_demo_video). The tests and benchmarks are left for
# scripts/test.sh, which turns the tests back on in the same tree (so their packages, not installed
# by `setup.sh --demo`, are not looked for here).
./scripts/build.sh -DNEOPIPE_BUILD_TESTING=OFF -DNEOPIPE_UNITY_BUILD=ON --target neopipe --target demo_video
out=build/demo
./build/apps/neopipe run "$out/marbles.avi" --out "$out/marbles_blobs.csv" --annotate "$out/marbles_annotated.mp4"
echo
echo "First rows of the blob table ($out/marbles_blobs.csv):"
head -n 6 "$out/marbles_blobs.csv"
echo "..."
echo "Annotated video: $out/marbles_annotated.mp4"
