#!/usr/bin/env python3
"""Reruns the navigation experiments of docs/navigation-experiments.md and prints their tables.

Each row is one `neopipe nav --trials N --json` run; the script only runs the commands and formats
their JSON (standard library only). Usage:

    scripts/nav_experiments.py [--neopipe build/apps/neopipe] [--out DIR] [--trials 1000] [TABLE ...]

TABLE is any of: sigmas, surveys, calibration, navigator, main, seeds, sensor, paired, throughput
(default: all). Runs are kept in DIR as
JSON and reused while the program is the same build. Worlds are made in DIR with
`neopipe sim world`, as the document's commands do. Every command is echoed on stderr.
"""

import argparse
import hashlib
import json
import math
import os
import shlex
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


def has_baseline(args):
    return bool(args.baseline or args.baseline_args)


def nav(args, world_path, *extra, trials=None, fresh=False, baseline=False):
    """One run's JSON. Runs are kept in the output folder, keyed by the command and the program's
    build, so that tables sharing a run (the paired comparisons) do not run it twice; `fresh` (the
    throughput) always runs. `baseline`: the run of the baseline (--baseline's build, else --neopipe,
    with --baseline-args)."""
    program = (args.baseline or args.neopipe) if baseline else args.neopipe
    if baseline:
        extra = (*extra, *shlex.split(args.baseline_args or ""))
    cmd = [program, "nav", "--world", world_path, "--trials", str(trials or args.trials), "--json", *extra]
    key = hashlib.sha1((" ".join(cmd) + str(os.path.getmtime(program))).encode()).hexdigest()[:16]
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
    """Journeys that reach the goal in one run and not the other, over the journeys both ran: the same
    start and goal, matched in order. Runs whose maps reach different pairs (a baseline that
    describes less) draw different pairs after the first that one cannot reach; those are left out."""
    ja, jb = a["journeys"], b["journeys"]
    by_pair = {}
    for y in jb:
        by_pair.setdefault((y["from"], y["to"]), []).append(y)
    pairs = []
    for x in ja:
        ys = by_pair.get((x["from"], x["to"]))
        if ys:
            pairs.append((x, ys.pop(0)))
    a_only = sum(reached(x) and not reached(y) for x, y in pairs)
    b_only = sum(reached(y) and not reached(x) for x, y in pairs)
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


def bins(j):
    """The forecast's calibration: per bin of planned R, (journeys, mean R, observed, Wilson 95% CI)."""
    edges = (0.0, 0.8, 0.9, 0.97, 1.0)
    out = []
    run = [x for x in j["journeys"] if x["outcome"] != "refused"]
    for lo, hi in zip(edges, edges[1:]):
        sel = [x for x in run if lo <= x["planned_reliability"] < hi or (hi == 1.0 and x["planned_reliability"] == 1.0)]
        if not sel:
            continue
        k, n = sum(reached(x) for x in sel), len(sel)
        out.append((lo, hi, n, sum(x["planned_reliability"] for x in sel) / n, k / n, wilson(k, n)))
    return out


def wilson(k, n, z=1.959963984540054):
    if n == 0:
        return (0.0, 1.0)
    p = k / n
    d = 1 + z * z / n
    c = p + z * z / (2 * n)
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return ((c - h) / d, (c + h) / d)


SIGMAS = (None, "0.25", "1", "1.5", "5")


def survey_label(sigma):
    return "rig survey" if sigma is None else f"`--sigma-map {sigma}`"


def sigma_table(args):
    """The issue-17 table: reached goal and the forecast's calibration at every survey error, on three
    sparse worlds and the dense one, with a paired comparison against a baseline build."""
    print("| world | survey | reached goal | 95% CI | forecast (mean R) | bins in their CI | backtracks | "
          "baseline | new only / baseline only | McNemar p |")
    print("|---|---|---:|---|---:|---:|---:|---:|---:|---:|")
    cases = [(100, w, sigma) for w in (1, 2, 3) for sigma in SIGMAS] + [(400, 1, "1")]
    for objects, seed, sigma in cases:
        w = world(args, objects, seed)
        extra = ["--sigma-map", sigma] if sigma else []
        j = nav(args, w, *extra)
        b = bins(j)
        inside = sum(lo_ci <= mean <= hi_ci for _, _, _, mean, _, (lo_ci, hi_ci) in b)
        backtracks = sum(x.get("backtracks", 0) for x in j["journeys"])
        cells = ["-", "-", "-"]
        if has_baseline(args) and (seed == 1):
            base = nav(args, w, *extra, baseline=True)
            a, bo, p = paired(j, base)
            cells = [pct(base["reached_goal_rate"]), f"{a} / {bo}", pvalue(p)]
        print(f"| w{objects}_{seed} | {survey_label(sigma)} | {pct(j['reached_goal_rate'])} | {ci(j)} | "
              f"{pct(j['mean_planned_reliability'])} | {inside} of {len(b)} | {backtracks} | {' | '.join(cells)} |",
              flush=True)


def calibration_table(args):
    """Per bin of planned R, pooled over the three sparse worlds: the forecast against the outcome."""
    print("| survey | R bin | journeys | mean R | reached | 95% CI | in CI |")
    print("|---|---|---:|---:|---:|---|---|")
    for sigma in SIGMAS:
        extra = ["--sigma-map", sigma] if sigma else []
        pooled = {"journeys": []}
        for seed in (1, 2, 3):
            pooled["journeys"] += nav(args, world(args, 100, seed), *extra)["journeys"]
        for lo, hi, n, mean, obs, (l, h) in bins(pooled):
            print(f"| {survey_label(sigma)} | [{lo:.2f}, {hi:.2f}) | {n} | {pct(mean)} | {pct(obs)} | "
                  f"[{100 * l:.1f}, {100 * h:.1f}] | {'yes' if l <= mean <= h else '**no**'} |", flush=True)


def navigator_table(args):
    """The navigator as the paper defines it (no heading memory) against the tracking extension."""
    print("| survey | tracking | paper | tracking only / paper only | McNemar p |")
    print("|---|---:|---:|---:|---:|")
    w = world(args, 100, 1)
    for sigma in (None, "1", "1.5"):
        extra = ["--sigma-map", sigma] if sigma else []
        t = nav(args, w, *extra)
        p_run = nav(args, w, *extra, "--navigator", "paper")
        a, b, p = paired(t, p_run)
        print(f"| {survey_label(sigma)} | {pct(t['reached_goal_rate'])} | {pct(p_run['reached_goal_rate'])} | "
              f"{a} / {b} | {pvalue(p)} |", flush=True)


def surveys_table(args):
    """Rates over many surveys: one survey's errors are shared by every journey of a run, so a run of
    1,000 journeys measures that survey, not the survey error. Per world and sigma, --surveys survey
    seeds of --survey-trials journeys each: the pooled rate, the spread between surveys, the forecast,
    its bins, and the paired comparison with a baseline build on the same journeys. The pooled
    journeys are written to OUT/surveys_wN_W_sS.json (the recovery credit's fit reads them)."""
    print("| world | survey | journeys | reached goal | 95% CI | per survey (min-max) | between-survey sd | "
          "forecast | bins in their CI | baseline | new only / baseline only | McNemar p |")
    print("|---|---|---:|---:|---|---|---:|---:|---:|---:|---:|---:|")
    pooled_by_sigma = {}
    # The sparse worlds at both survey errors, pooled below; the dense world at 1 mm, on its own.
    cases = [(100, w_seed, sigma) for sigma in ("1", "1.5") for w_seed in (1, 2, 3)] + [(400, 1, "1")]
    for objects, w_seed, sigma in cases:
        w = world(args, objects, w_seed)
        runs, bases = [], []
        for seed in range(1, args.surveys + 1):
            extra = ["--sigma-map", sigma, "--seed", str(seed)]
            runs.append(nav(args, w, *extra, trials=args.survey_trials))
            if has_baseline(args):
                bases.append(nav(args, w, *extra, trials=args.survey_trials, baseline=True))
        journeys = [x for r in runs for x in r["journeys"] if x["outcome"] != "refused"]
        if objects == 100:
            pooled_by_sigma.setdefault(sigma, []).extend(journeys)
        # Every survey's journeys in one file, for scripts/fit_recovery_credit.py.
        with open(os.path.join(args.out, f"surveys_w{objects}_{w_seed}_s{sigma}.json"), "w") as f:
            json.dump({"journeys": journeys}, f)
        k, n = sum(reached(x) for x in journeys), len(journeys)
        rates = [sum(reached(x) for x in r["journeys"]) / len(r["journeys"]) for r in runs]
        mean_rate = sum(rates) / len(rates)
        sd = math.sqrt(sum((r - mean_rate) ** 2 for r in rates) / max(1, len(rates) - 1))
        forecast = sum(x["planned_reliability"] for x in journeys) / n
        b = bins({"journeys": journeys})
        inside = sum(lo_ci <= mean <= hi_ci for _, _, _, mean, _, (lo_ci, hi_ci) in b)
        cells = ["-", "-", "-"]
        if bases:
            a_only = b_only = 0
            for r, base in zip(runs, bases):
                a, bo, _ = paired(r, base)
                a_only, b_only = a_only + a, b_only + bo
            base_rate = sum(sum(reached(x) for x in r["journeys"]) for r in bases) / sum(
                len(r["journeys"]) for r in bases)
            cells = [pct(base_rate), f"{a_only} / {b_only}", pvalue(mcnemar(a_only, b_only))]
        lo, hi = wilson(k, n)
        print(f"| w{objects}_{w_seed} | {survey_label(sigma)} | {n} | {pct(k / n)} | [{100 * lo:.1f}, {100 * hi:.1f}] | "
              f"{pct(min(rates))}-{pct(max(rates))} | {100 * sd:.1f} pts | {pct(forecast)} | "
              f"{inside} of {len(b)} | {' | '.join(cells)} |", flush=True)
    print("\nPooled over the three sparse worlds and every survey:\n")
    print("| survey | R bin | journeys | mean R | reached | 95% CI | in CI |")
    print("|---|---|---:|---:|---:|---|---|")
    for sigma, journeys in pooled_by_sigma.items():
        k, n = sum(reached(x) for x in journeys), len(journeys)
        lo, hi = wilson(k, n)
        mean = sum(x["planned_reliability"] for x in journeys) / n
        print(f"| {survey_label(sigma)} | all | {n} | {pct(mean)} | {pct(k / n)} | [{100 * lo:.1f}, {100 * hi:.1f}] | "
              f"{'yes' if lo <= mean <= hi else '**no**'} |")
        for blo, bhi, m, bmean, obs, (l, h) in bins({"journeys": journeys}):
            print(f"| {survey_label(sigma)} | [{blo:.2f}, {bhi:.2f}) | {m} | {pct(bmean)} | {pct(obs)} | "
                  f"[{100 * l:.1f}, {100 * h:.1f}] | {'yes' if l <= bmean <= h else '**no**'} |", flush=True)


TABLES = {"sigmas": sigma_table, "surveys": surveys_table, "calibration": calibration_table, "navigator": navigator_table,
          "main": main_table, "seeds": seeds_table, "sensor": sensor_table, "paired": paired_table,
          "throughput": throughput_table}


def parse():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--neopipe", default="build/apps/neopipe")
    p.add_argument("--out", default="build/nav-experiments", help="folder for the worlds")
    p.add_argument("--trials", type=int, default=1000)
    p.add_argument("--baseline", help="another neopipe build to compare with, journey by journey (sigmas, surveys)")
    p.add_argument("--baseline-args", help="options the baseline runs add, e.g. '--descriptions paper' (the baseline "
                   "is then --neopipe itself unless --baseline names another build)")
    p.add_argument("--surveys", type=int, default=5, help="survey seeds per world and sigma (surveys table)")
    p.add_argument("--survey-trials", type=int, default=200, help="journeys per survey (surveys table)")
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
