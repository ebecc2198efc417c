#!/usr/bin/env python3
"""Reruns the navigation experiments of docs/navigation-experiments.md and prints their tables.

Each row is one `neopipe nav --trials N --json` run; the script only runs the commands and formats
their JSON (standard library only). Usage:

    scripts/nav_experiments.py [--neopipe build/apps/neopipe] [--out DIR] [--trials 1000] [TABLE ...]

TABLE is any of: main, seeds, sensor, paired, throughput (default: all). Runs are kept in DIR as
JSON and reused while the program is the same build. Worlds are made in DIR with
`neopipe sim world`, as the document's commands do. Every command is echoed on stderr.
"""

import argparse
import hashlib
import json
import math
import os
import subprocess
import sys
import time

OUTCOMES = ["success_direct", "success_recovered", "success_unaware", "fail_lost", "fail_unrecoverable",
            "fail_unaware"]


def run(cmd):
    print("+ " + " ".join(cmd), file=sys.stderr, flush=True)
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout


def world(args, objects, seed):
    path = os.path.join(args.out, f"w{objects}_{seed}.yaml")
    if not os.path.exists(path):
        run([args.neopipe, "sim", "world", "--objects", str(objects), "--seed", str(seed), "--out", path])
    return path


def nav(args, world_path, *extra, trials=None, fresh=False):
    """One run's JSON. Runs are kept in the output folder, keyed by the command and the program's
    build, so that tables sharing a run (the paired comparisons) do not run it twice; `fresh` (the
    throughput) always runs."""
    cmd = [args.neopipe, "nav", "--world", world_path, "--trials", str(trials or args.trials), "--json", *extra]
    key = hashlib.sha1((" ".join(cmd) + str(os.path.getmtime(args.neopipe))).encode()).hexdigest()[:16]
    cached = os.path.join(args.out, f"run-{key}.json")
    if not fresh and os.path.exists(cached):
        with open(cached) as f:
            return json.load(f)
    start = time.monotonic()
    j = json.loads(run(cmd))
    j["wall"] = time.monotonic() - start
    with open(cached, "w") as f:
        json.dump(j, f)
    return j


def mcnemar(a_only, b_only):
    """Exact two-sided McNemar (sign) test."""
    n = a_only + b_only
    if n == 0:
        return 1.0
    k = min(a_only, b_only)
    return min(1.0, 2 * sum(math.comb(n, i) for i in range(k + 1)) / 2 ** n)


def reached(journey):
    return journey["outcome"].startswith("success")


def paired(a, b):
    ja, jb = a["journeys"], b["journeys"]
    assert [(x["from"], x["to"]) for x in ja] == [(x["from"], x["to"]) for x in jb], "not the same journeys"
    a_only = sum(reached(x) and not reached(y) for x, y in zip(ja, jb))
    b_only = sum(reached(y) and not reached(x) for x, y in zip(ja, jb))
    return a_only, b_only, mcnemar(a_only, b_only)


def pvalue(p):
    return f"{p:.2g}" if p >= 1e-3 else f"{p:.1e}"


def paired_table(args):
    print("| world, criterion | with recovery | without | recovery only / stripped only | McNemar p |")
    print("|---|---:|---:|---:|---:|")
    for objects in (100, 400):
        w = world(args, objects, 1)
        for cost in ("distance", "ratio", "reliability"):
            on = nav(args, w, "--cost", cost)
            off = nav(args, w, "--cost", cost, "--no-recovery")
            a, b, p = paired(on, off)
            print(f"| w{objects}, {cost} | {pct(on['reached_goal_rate'])} | {pct(off['reached_goal_rate'])} | "
                  f"{a} / {b} | {pvalue(p)} |", flush=True)
    print()
    print("| world | a against b | a | b | a only / b only | McNemar p |")
    print("|---|---|---:|---:|---:|---:|")
    for objects in (100, 400):
        w = world(args, objects, 1)
        runs = {cost: nav(args, w, "--cost", cost) for cost in ("distance", "ratio", "reliability")}
        for x, y in (("ratio", "distance"), ("reliability", "distance"), ("ratio", "reliability")):
            a, b, p = paired(runs[x], runs[y])
            print(f"| w{objects} | {x} against {y} | {pct(runs[x]['reached_goal_rate'])} | "
                  f"{pct(runs[y]['reached_goal_rate'])} | {a} / {b} | {pvalue(p)} |", flush=True)


def pct(x):
    return f"{100 * x:.1f}%"


def ci(j):
    low, high = j["reached_goal_ci95"]
    return f"[{100 * low:.1f}, {100 * high:.1f}]"


def main_table(args):
    print("| world, run | reached goal | 95% CI | direct | recovered | unaware ok | lost | unrecoverable | "
          "unaware fail | planned D mm | planned R | arm travel mm |")
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for objects in (100, 400):
        w = world(args, objects, 1)
        for cost in ("reliability", "ratio", "distance"):
            for recovery in (True, False):
                extra = ["--cost", cost] + ([] if recovery else ["--no-recovery"])
                j = nav(args, w, *extra)
                name = f"w{objects}, {cost}" + ("" if recovery else " `--no-recovery`")
                counts = " | ".join(str(j["outcomes"][o]) for o in OUTCOMES)
                print(f"| {name} | {pct(j['reached_goal_rate'])} | {ci(j)} | {counts} | "
                      f"{j['mean_planned_distance']:.1f} | {pct(j['mean_planned_reliability'])} | "
                      f"{j['mean_arm_travel']:.1f} |", flush=True)


def seeds_table(args):
    print("| run | reliability (default) | ratio |")
    print("|---|---:|---:|")
    runs = [(1, 1), (1, 2), (1, 3), (2, 1), (3, 1)]
    totals = {"reliability": [0, 0], "ratio": [0, 0]}
    for world_seed, seed in runs:
        w = world(args, 100, world_seed)
        cells = []
        for cost in ("reliability", "ratio"):
            j = nav(args, w, "--cost", cost, "--seed", str(seed))
            totals[cost][0] += j["reached_goal"]
            totals[cost][1] += j["trials"]
            cells.append(f"{pct(j['reached_goal_rate'])} {ci(j)}")
        print(f"| world seed {world_seed}, `--seed {seed}` | {cells[0]} | {cells[1]} |", flush=True)
    r, q = totals["reliability"], totals["ratio"]
    print(f"| all {r[1]:,} | **{100 * r[0] / r[1]:.2f}%** | **{100 * q[0] / q[1]:.2f}%** |")


def sensor_table(args):
    print("| survey | distance: goal / planned D | ratio: goal / planned D | reliability: goal / planned D | "
          "compromise's place |")
    print("|---|---:|---:|---:|---:|")
    w = world(args, 100, 1)
    for sigma in (None, "0.25", "1", "5"):
        cells = []
        d = {}
        for cost in ("distance", "ratio", "reliability"):
            extra = ["--cost", cost] + (["--sigma-map", sigma] if sigma else [])
            j = nav(args, w, *extra)
            d[cost] = j["mean_planned_distance"]
            cells.append(f"{pct(j['reached_goal_rate'])} / {d[cost]:.1f}")
            label = (f"rig survey ({j['survey']['rms_error']:.4f} mm RMS)" if sigma is None
                     else f"`--sigma-map {sigma}`")
        span = d["reliability"] - d["distance"]
        place = f"{100 * (d['ratio'] - d['distance']) / span:.0f}%" if span > 0 else "-"
        print(f"| {label} | {' | '.join(cells)} | {place} |", flush=True)


def throughput_table(args):
    print("| threads | seconds | frames | frames/s |")
    print("|---:|---:|---:|---:|")
    w = world(args, 100, 1)
    nav(args, w, trials=1, fresh=True)  # the survey's session into the calibration cache first
    for threads in ("2", "1"):
        for _ in range(3):
            j = nav(args, w, "--threads", threads, fresh=True)
            print(f"| {threads} | {j['seconds']:.2f} | {j['frames']:,} | {j['frames_per_second']:,.0f} |", flush=True)


TABLES = {"main": main_table, "seeds": seeds_table, "sensor": sensor_table, "paired": paired_table,
          "throughput": throughput_table}


def parse():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--neopipe", default="build/apps/neopipe")
    p.add_argument("--out", default="build/nav-experiments", help="folder for the worlds")
    p.add_argument("--trials", type=int, default=1000)
    p.add_argument("tables", nargs="*", metavar="TABLE", help=f"any of {', '.join(TABLES)} (default: all)")
    args = p.parse_args()
    unknown = [t for t in args.tables if t not in TABLES]
    if unknown:
        p.error(f"unknown table {unknown[0]} (choose from {', '.join(TABLES)})")
    return args


if __name__ == "__main__":
    args = parse()
    os.makedirs(args.out, exist_ok=True)
    for name in args.tables or TABLES:
        print(f"\n## {name} ({args.trials} journeys per row)\n", flush=True)
        TABLES[name](args)
