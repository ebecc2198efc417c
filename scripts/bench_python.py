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

The C++ figure is taken two ways: the `neopipe bench` program itself, and the same timing loop
(bench/blob_bench.cpp's, on the same arrays) run inside this process in turn with each Python
timed run, so that a machine busy with other work slows both alike: the ratio that counts is
run() over the C++ loop timed next to it, the median over every pair. It prints every round, the
medians, and exits 1 if that ratio is below 0.9.
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


def time_run_once(frames, threads, min_seconds):
    n = counted = 0
    t0 = None
    stream = neopipe.run(itertools.cycle(frames), threshold=_core.dots_threshold, threads=threads)
    for _ in stream:
        n += 1
        if n == 3:  # warm: the executor and its buffers are made on the first frames
            t0 = time.perf_counter()
        elif n > 3:
            counted += 1
            if counted % 64 == 0 and time.perf_counter() - t0 >= min_seconds:
                break
    return counted / (time.perf_counter() - t0)


def paired(frames, threads, min_seconds, repeats=5):
    """(C++ loop, run()) frames/s, each the median of `repeats` timed runs taken in turn, and the median ratio."""
    cpp, py, ratios = [], [], []
    for _ in range(repeats):
        cpp.append(_core.time_executor(frames, _core.dots_threshold, threads, min_seconds))
        py.append(time_run_once(frames, threads, min_seconds))
        ratios.append(py[-1] / cpp[-1])
    return statistics.median(cpp), statistics.median(py), ratios


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
    print(f"dots {a.size}, {a.threads} thread(s); frames/s, medians of 5 timed runs of >= {a.min_seconds} s each")
    print(f"{'round':>5} {'neopipe bench':>13} {'C++ loop':>9} {'run()':>8} {'run/loop':>9} {'run/bench':>10}"
          f" {'process()':>10}")
    bench, loop, run, ratios, proc = [], [], [], [], []
    for r in range(a.rounds):
        bench.append(cpp_fps(a.cli, a.size, a.threads))
        c, p_, rs = paired(frames, a.threads, a.min_seconds)
        loop.append(c)
        run.append(p_)
        ratios += rs
        proc.append(time_process(frames, a.min_seconds))
        print(f"{r + 1:>5} {bench[-1]:>13.0f} {c:>9.0f} {p_:>8.0f} {statistics.median(rs):>9.3f}"
              f" {p_ / bench[-1]:>10.3f} {proc[-1]:>10.0f}")
    b, c, m = statistics.median(bench), statistics.median(loop), statistics.median(run)
    ratio = statistics.median(ratios)
    print(f"{'median':>5} {b:>13.0f} {c:>9.0f} {m:>8.0f} {ratio:>9.3f} {m / b:>10.3f} {statistics.median(proc):>10.0f}")
    print(f"run() / C++ loop timed beside it: median {ratio:.3f} over {len(ratios)} pairs "
          f"(quartiles {statistics.quantiles(ratios, n=4)[0]:.3f} .. {statistics.quantiles(ratios, n=4)[2]:.3f})")
    print("process() is one frame at a time on the calling thread, no worker threads: compare it with 1 thread")
    return 0 if ratio >= 0.9 else 1


if __name__ == "__main__":
    sys.exit(main())
