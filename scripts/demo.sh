#!/usr/bin/env bash
# The README's first command: set up, build, and run neopipe on the demo video the build generates
# (24 marbles rolling over an unevenly lit table, 640x480, 120 frames).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh
out=build/demo
./build/apps/neopipe run "$out/marbles.avi" --out "$out/marbles_blobs.csv" --annotate "$out/marbles_annotated.mp4"
echo
echo "First rows of the blob table ($out/marbles_blobs.csv):"
head -n 6 "$out/marbles_blobs.csv"
echo "..."
echo "Annotated video: $out/marbles_annotated.mp4"
