#!/usr/bin/env python3
"""Fits the map-maker's recovery credit (nav/mapmaker/reliability.hpp, RecoveryCredit) to
`neopipe nav --trials N --json` runs, and checks it on held-out runs.

A step rated R on its first try (the planner's R, each journey's "steps" in the JSON) is forecast to
cost the journey nothing with 1 - (1 - share) (1 - R): the navigator catches and undoes that share
of the step's mistakes. The share maximises the likelihood of the journeys' outcomes (reached the
goal or not) under the forecast, the product over their steps; a grid of 0.01 is fine enough. With
--by-kind a share per kind of step (OBVIOUS, ISOL, FAR, NEAR, and TRAJ for every slide) is fitted
too, and the reports use it. Standard library only. Usage:

    scripts/fit_recovery_credit.py --fit RUN.json ... [--check RUN.json ...] [--by-kind]
"""

import argparse
import json
import math


def kind_of(step):
    """"TRAJN-NEAR 4 -> 7" -> TRAJ; "NEAR 4 -> 7" -> NEAR: trajectories as one kind, whatever their via."""
    name = step.split()[0]
    return "TRAJ" if name.startswith("TRAJ") else name


def journeys(paths):
    out = []
    for path in paths:
        with open(path) as f:
            for x in json.load(f)["journeys"]:
                if x["outcome"] == "refused":
                    continue
                kinds = [(s["R"], kind_of(s["step"])) for s in x["steps"]]
                out.append((kinds, x["outcome"].startswith("success")))
    return out


def forecast(steps, share):
    p = 1.0
    for r, kind in steps:
        p *= 1 - (1 - share[kind] if isinstance(share, dict) else 1 - share) * (1 - r)
    return p


def log_likelihood(data, share):
    total = 0.0
    for steps, ok in data:
        p = min(max(forecast(steps, share), 1e-9), 1 - 1e-9)
        total += math.log(p if ok else 1 - p)
    return total


GRID = [i / 100 for i in range(100)]


def wilson(k, n, z=1.959963984540054):
    p = k / n
    d = 1 + z * z / n
    c = p + z * z / (2 * n)
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return (c - h) / d, (c + h) / d


def report(name, data, share):
    n = len(data)
    f = [forecast(s, share) for s, _ in data]
    ok = [o for _, o in data]
    print(f"{name}: {n} journeys, reached {100 * sum(ok) / n:.2f}%, forecast {100 * sum(f) / n:.2f}% "
          f"(first try {100 * sum(forecast(s, 0.0) for s, _ in data) / n:.2f}%)")
    for lo, hi in ((0, 0.8), (0.8, 0.9), (0.9, 0.97), (0.97, 1.0000001)):
        sel = [(r, o) for r, o in zip(f, ok) if lo <= r < hi]
        if not sel:
            continue
        k, m = sum(o for _, o in sel), len(sel)
        low, high = wilson(k, m)
        mean = sum(r for r, _ in sel) / m
        print(f"  R in [{lo}, {min(hi, 1)}): {m} journeys, forecast {100 * mean:.1f}%, reached {100 * k / m:.1f}% "
              f"[{100 * low:.1f}, {100 * high:.1f}]{'' if low <= mean <= high else '  OUTSIDE'}")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--fit", nargs="+", required=True, help="trials JSON to fit on")
    p.add_argument("--check", nargs="*", default=[], help="trials JSON to check the fit on (held out)")
    p.add_argument("--by-kind", action="store_true", help="also fit one share per kind of step")
    args = p.parse_args()
    data = journeys(args.fit)
    share = max(GRID, key=lambda s: log_likelihood(data, s))
    print(f"one share: {share:.2f} (log-likelihood {log_likelihood(data, share):.1f}, "
          f"without credit {log_likelihood(data, 0.0):.1f})")
    if args.by_kind:
        kinds = {k: share for k in sorted({kind for steps, _ in data for _, kind in steps})}
        for _ in range(3):
            for k in kinds:
                kinds[k] = max(GRID, key=lambda s: log_likelihood(data, {**kinds, k: s}))
        print(f"by kind: {kinds} (log-likelihood {log_likelihood(data, kinds):.1f})")
    credit = kinds if args.by_kind else share
    report("fitted on", data, credit)
    for path in args.check:
        report(path, journeys([path]), credit)
    if args.check and len(args.check) > 1:
        report("all held out", journeys(args.check), credit)


if __name__ == "__main__":
    main()
