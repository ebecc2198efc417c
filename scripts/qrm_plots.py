#!/usr/bin/python3
"""Draws the figures of spec qrm.md §10 from `neopipe qrm experiment` CSV and prints their tables.

Usage (Debian's python3 with python3-matplotlib and numpy; no pandas needed, though the CSV reads
with pandas.read_csv as it is):

    scripts/qrm_plots.py --runs DIR_K/qrm_runs.csv --sizes DIR_N/qrm_runs.csv --out docs/images

DIR_K: one world size, several k (M1-M4 and the RNG against the number of images, per k);
DIR_N: several world sizes, one k (the update time M5 against the number of landmarks).
Writes qrm_metrics.png, qrm_rng.png and qrm_update_time.png to --out and prints Markdown tables.
"""

import argparse
import csv
import math
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

FIELDS = ["m1", "m2", "m3", "m4", "m5_us", "rng_precision", "rng_recall", "rng_equal", "inconsistent", "lost",
          "triples"]


def load(path):
    """{(marbles, k): {field: array [runs, images]}}."""
    rows = defaultdict(lambda: defaultdict(dict))
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            key = (int(r["marbles"]), int(r["k"]))
            for field in FIELDS:
                rows[key][field][(int(r["run"]), int(r["image"]))] = float(r[field])
    out = {}
    for key, fields in rows.items():
        runs = sorted({run for run, _ in fields["m1"]})
        images = sorted({image for _, image in fields["m1"]})
        out[key] = {field: np.array([[values[(run, image)] for image in images] for run in runs])
                    for field, values in fields.items()}
    return out


def mean_ci(a):
    """Mean over runs (axis 0) and its 95% normal interval half-width."""
    m = a.mean(axis=0)
    half = 1.96 * a.std(axis=0, ddof=1) / math.sqrt(a.shape[0]) if a.shape[0] > 1 else np.zeros_like(m)
    return m, half


def curves(ax, data, field, title, ylabel, log=False):
    for (marbles, k), d in sorted(data.items(), key=lambda kv: kv[0][1]):
        m, half = mean_ci(d[field])
        x = np.arange(1, len(m) + 1)
        ax.plot(x, m, label=f"k = {k}")
        ax.fill_between(x, m - half, m + half, alpha=0.25)
    ax.set_title(title)
    ax.set_xlabel("images")
    ax.set_ylabel(ylabel)
    if log:
        ax.set_yscale("log")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--runs", required=True)
    p.add_argument("--sizes")
    p.add_argument("--out", required=True)
    p.add_argument("--caption", default="")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    data = load(a.runs)
    marbles = sorted({m for m, _ in data})
    runs = next(iter(data.values()))["m1"].shape[0]
    note = f"{runs} runs, {marbles[0]} marbles; mean and 95% CI. {a.caption}"

    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    curves(axes[0][0], data, "m1", "M1: incorrect states removed", "%")
    curves(axes[0][1], data, "m2", "M2: triples with all three relations single", "%")
    curves(axes[1][0], data, "m3", "M3: sum of c_ij over RNG candidates", "M3", log=True)
    curves(axes[1][1], data, "m4", "M4: open wrong states not adjacent to the truth", "%")
    fig.suptitle("QRM map building (spec qrm.md §10): " + note)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "qrm_metrics.png"), dpi=90)

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
    curves(axes[0], data, "rng_precision", "estimated RNG: precision (true / candidates)", "precision")
    curves(axes[1], data, "rng_recall", "estimated RNG: recall (candidates / true)", "recall")
    for (_, k), d in sorted(data.items(), key=lambda kv: kv[0][1]):
        # candidates / true edges = recall / precision: 1 when the estimate is the true RNG.
        ratio = d["rng_recall"] / np.maximum(d["rng_precision"], 1e-9)
        m, half = mean_ci(ratio)
        x = np.arange(1, len(m) + 1)
        axes[2].plot(x, m, label=f"k = {k}")
        axes[2].fill_between(x, m - half, m + half, alpha=0.25)
    axes[2].set_yscale("log")
    axes[2].set_title("candidates / true RNG edges (1: the true RNG)")
    axes[2].set_ylabel("ratio")
    axes[2].set_xlabel("images")
    axes[2].grid(alpha=0.3)
    axes[2].legend(fontsize=8)
    fig.suptitle("The RNG estimate converging to the true RNG: " + note)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "qrm_rng.png"), dpi=90)

    print(f"### M1-M4 and the RNG ({note})\n")
    print("| k | images | M1 % | M2 % | M3 | M4 % | RNG precision | RNG recall | RNG exact (% runs) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for (_, k), d in sorted(data.items(), key=lambda kv: kv[0][1]):
        for image in (1, 5, 10, 25, d["m1"].shape[1]):
            i = image - 1
            if i >= d["m1"].shape[1]:
                continue
            print(f"| {k} | {image} | {d['m1'][:, i].mean():.1f} | {d['m2'][:, i].mean():.1f} | "
                  f"{d['m3'][:, i].mean():.3g} | {d['m4'][:, i].mean():.1f} | {d['rng_precision'][:, i].mean():.3f} | "
                  f"{d['rng_recall'][:, i].mean():.3f} | {100 * d['rng_equal'][:, i].mean():.0f} |")
    incons = sum(d["inconsistent"].sum() for d in data.values())
    lost = sum(d["lost"][:, -1].sum() for d in data.values())
    print(f"\ninconsistent measurements: {incons:.0f}; final relations without their true state: {lost:.0f}\n")

    fig, axes = plt.subplots(1, 2, figsize=(13, 4.8))
    for (_, k), d in sorted(data.items(), key=lambda kv: kv[0][1]):
        m, half = mean_ci(d["m5_us"])
        axes[0].plot(np.arange(1, len(m) + 1), m, label=f"k = {k}")
    axes[0].set_yscale("log")
    axes[0].set_title(f"M5 per image ({marbles[0]} marbles)")
    axes[0].set_xlabel("images")
    axes[0].set_ylabel("µs per update (measure + fuse one triple)")
    axes[0].grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    if a.sizes:
        sizes = load(a.sizes)
        n = np.array(sorted(m for m, _ in sizes))
        k = sorted({k for _, k in sizes})[0]
        # Mean over every update of a run (images weighted by their triples), then over runs.
        per_run = [np.array([(sizes[(m, k)]["m5_us"] * sizes[(m, k)]["triples"]).sum(axis=1) /
                             sizes[(m, k)]["triples"].sum(axis=1)]).ravel() for m in n]
        means = np.array([r.mean() for r in per_run])
        halves = np.array([1.96 * r.std(ddof=1) / math.sqrt(len(r)) for r in per_run])
        axes[1].errorbar(n, means, yerr=halves, marker="o", capsize=3, label=f"k = {k}")
        slope, intercept = np.polyfit(np.log(n), np.log(means), 1)
        axes[1].plot(n, np.exp(intercept) * n ** slope, "--", label=f"fit: ∝ N^{slope:.2f}")
        axes[1].set_xscale("log")
        axes[1].set_yscale("log")
        axes[1].set_title(f"M5 against landmarks ({len(per_run[0])} runs each, 50 images)")
        axes[1].set_xlabel("landmarks N (marbles in the world)")
        axes[1].set_ylabel("µs per update, mean over the run")
        axes[1].grid(alpha=0.3, which="both")
        axes[1].legend(fontsize=8)
        print("### M5 against landmarks\n")
        print("| landmarks | k | µs per update (mean, 95% CI) |")
        print("|---|---|---|")
        for m, mean, half in zip(n, means, halves):
            print(f"| {m} | {k} | {mean:.1f} ± {half:.1f} |")
        print(f"\npower-law fit: M5 ∝ N^{slope:.2f}\n")
    fig.suptitle("Update time M5 (wall time of one measurement and its propagation; machine shared)")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "qrm_update_time.png"), dpi=90)


if __name__ == "__main__":
    main()
