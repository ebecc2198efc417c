#!/usr/bin/env python3
"""Throughput of neopipe from Python against the C++ `neopipe bench` figure, measured in the same run.

    PYTHONPATH=build/python python3 scripts/bench_python.py [--size 640x480] [--threads 2] [--rounds 3]

The frames are `neopipe bench`'s dots frames (about 100 shaded disks; the same generator and
seeds), handed in from Python one at a time, through the same graph (the built-in blob graph,
gray, threshold 128, 8-connected). Each round runs `neopipe bench --case dots --json` (the
median of its 5 timed runs) and then, in this process, for the same minimum time each:

  run      neopipe.run(frames): frames from a Python iterator, several in flight, one table
           (a numpy structured array) yielded per frame: the streaming path.
  process  graph.process(frame) in a loop: one frame at a time on the calling thread, the engine
           inline (no executor, no worker threads), whole frames.

It prints every round and the medians, and the ratio run / C++ (target: >= 0.9).
"""

import argparse
import itertools
import json
import os
import pathlib
import statistics
import subprocess
import sys
import time

import neopipe
from neopipe import _core

ROOT = pathlib.Path(__file__).resolve().parents[1]


def cpp_fps(cli, size, threads):
    out = subprocess.run([str(cli), "bench", "--case", "dots", "--size", size, "--threads", str(threads), "--json"],
                         capture_output=True, text=True, check=True).stdout
    return next(r["fps"] for r in json.loads(out)["records"] if r["impl"] == "neopipe")


def frames_for(size):
    w, h = (int(v) for v in size.split("x"))
    # bench/blob_bench.cpp: 8 distinct frames, seeds 1000 i + 17.
    return [_core.dots_frame(w, h, 100, 1000 * i + 17) for i in range(8)]


def time_run(frames, threads, min_seconds, repeats=5):
    rates = []
    for _ in range(repeats):
        n = 0
        t0 = None
        stream = neopipe.run(itertools.cycle(frames), threshold=_core.dots_threshold, threads=threads)
        for table in stream:
            n += 1
            if n == 3:  # warm: the executor and its buffers are made on the first frames
                t0 = time.perf_counter()
                counted = 0
            elif n > 3:
                counted += 1
                if counted % 64 == 0 and time.perf_counter() - t0 >= min_seconds:
                    break
        rates.append(counted / (time.perf_counter() - t0))
        del stream
    return statistics.median(rates)


def time_process(frames, min_seconds, repeats=5):
    rates = []
    graph = neopipe.Graph.blobs(threshold=_core.dots_threshold)
    for f in frames[:3]:
        graph.process(f)
    for _ in range(repeats):
        n = 0
        t0 = time.perf_counter()
        while True:
            for f in frames:
                graph.process(f)
            n += len(frames)
            if time.perf_counter() - t0 >= min_seconds:
                break
        rates.append(n / (time.perf_counter() - t0))
    return statistics.median(rates)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--size", default="640x480")
    p.add_argument("--threads", type=int, default=os.cpu_count())
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--min-seconds", type=float, default=0.3, help="each timed run (as neopipe bench's)")
    p.add_argument("--cli", default=os.environ.get("NEOPIPE_CLI", ROOT / "build" / "apps" / "neopipe"))
    a = p.parse_args()
    frames = frames_for(a.size)
    print(f"dots {a.size}, {a.threads} thread(s); frames/s, median of 5 timed runs of >= {a.min_seconds} s each")
    print(f"{'round':>5} {'C++ bench':>10} {'run()':>10} {'run/C++':>8}   {'process() (1 thread)':>20}")
    cpp, run, proc = [], [], []
    for r in range(a.rounds):
        cpp.append(cpp_fps(a.cli, a.size, a.threads))
        run.append(time_run(frames, a.threads, a.min_seconds))
        proc.append(time_process(frames, a.min_seconds))
        print(f"{r + 1:>5} {cpp[-1]:>10.0f} {run[-1]:>10.0f} {run[-1] / cpp[-1]:>8.3f}   {proc[-1]:>20.0f}")
    c, m = statistics.median(cpp), statistics.median(run)
    print(f"{'median':>5} {c:>10.0f} {m:>10.0f} {m / c:>8.3f}   {statistics.median(proc):>20.0f}")
    one = cpp_fps(a.cli, a.size, 1)
    print(f"C++ bench at 1 thread: {one:.0f} frames/s; process() / that: {statistics.median(proc) / one:.3f}")
    return 0 if m / c >= 0.9 else 1


if __name__ == "__main__":
    sys.exit(main())
