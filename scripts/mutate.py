#!/usr/bin/python3
"""Hand-written mutation testing for neopipe (issue 18, section 3).

Each mutant in the mutant list (tests/mutation/mutants.json by default) names a source file, an
exact snippet of it and its replacement. For each mutant the script

  1. checks the snippet occurs exactly once (or picks occurrence N with "occurrence": N, 1-based),
  2. writes the mutated file,
  3. rebuilds only the targets that guard that file (`cmake --build BUILD --target ...`),
  4. runs the guarding test binaries (GoogleTest, stopping at the first failure),
  5. ALWAYS restores the file (try/finally, then checks the bytes and `git diff --quiet`),

and records one of:

  killed        a guarding test failed, crashed or timed out
  survived      every guarding test passed with the mutant in place
  build_failed  the mutant does not compile (not counted either way)

Results go to OUT/results.csv and OUT/summary.json, with OUT/logs/ID.log per mutant.

Examples:
  /usr/bin/python3 scripts/mutate.py --list
  /usr/bin/python3 scripts/mutate.py --out /tmp/mut            # every mutant (tens of minutes)
  /usr/bin/python3 scripts/mutate.py --out /tmp/mut --only K01 P03

The build folder must already be configured (see --build); the script builds in it with one job
unless --jobs says otherwise. Do not edit the mutated sources while it runs.
"""

from __future__ import annotations

import argparse
import csv
import datetime as dt
import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_MUTANTS = ROOT / "tests" / "mutation" / "mutants.json"
DEFAULT_BUILD = ROOT / "build-mut"
FAILED_RE = re.compile(r"^\[  FAILED  \] (\S+)", re.M)


class Abort(Exception):
    pass


def on_sigterm(signum, frame):  # so that `finally` restores the file on kill -TERM too
    raise SystemExit(128 + signum)


def load_mutants(path: Path) -> tuple[dict, list[dict]]:
    data = json.loads(path.read_text())
    guards = data.get("guards", {})
    mutants = data["mutants"]
    seen = set()
    for m in mutants:
        for key in ("id", "file", "original", "replacement", "description", "guard"):
            if key not in m:
                raise Abort(f"mutant {m.get('id', '?')}: missing '{key}'")
        if m["id"] in seen:
            raise Abort(f"duplicate mutant id {m['id']}")
        seen.add(m["id"])
        if m["guard"] not in guards:
            raise Abort(f"mutant {m['id']}: unknown guard '{m['guard']}' (known: {', '.join(guards)})")
        if m["original"] == m["replacement"]:
            raise Abort(f"mutant {m['id']}: the replacement equals the original")
    return guards, mutants


def locate(text: str, m: dict) -> int:
    """Offset of the snippet to replace; raises Abort unless it is unambiguous."""
    snippet = m["original"]
    offsets = [i for i in range(len(text)) if text.startswith(snippet, i)]
    if not offsets:
        raise Abort(f"mutant {m['id']}: snippet not found in {m['file']}: {snippet!r}")
    occurrence = m.get("occurrence")
    if occurrence is None:
        if len(offsets) != 1:
            raise Abort(f"mutant {m['id']}: snippet occurs {len(offsets)} times in {m['file']}; "
                        f"add \"occurrence\": N (1..{len(offsets)})")
        return offsets[0]
    if not 1 <= occurrence <= len(offsets):
        raise Abort(f"mutant {m['id']}: occurrence {occurrence} of {len(offsets)}")
    return offsets[occurrence - 1]


def line_of(text: str, offset: int) -> int:
    return text.count("\n", 0, offset) + 1


def git_clean(path: Path) -> bool:
    return subprocess.run(["git", "-C", str(ROOT), "diff", "--quiet", "--", str(path)]).returncode == 0


def run_logged(cmd, log, timeout, cwd=None, env=None):
    """Runs cmd in its own process group; returns (returncode or 'timeout', output)."""
    log.write(f"$ {' '.join(map(str, cmd))}\n")
    log.flush()
    p = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         start_new_session=True, text=True, errors="replace")
    try:
        out, _ = p.communicate(timeout=timeout)
        rc = p.returncode
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, _ = p.communicate()
        rc = "timeout"
    except BaseException:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        raise
    log.write(out)
    log.write(f"[exit: {rc}]\n")
    log.flush()
    return rc, out


def build(args, targets, log):
    cmd = ["cmake", "--build", str(args.build), "-j", str(args.jobs), "--target", *targets]
    rc, out = run_logged(cmd, log, args.build_timeout)
    return rc == 0


def run_tests(args, tests, log, deadline):
    """Runs each guarding binary; returns (passed, first failing test or reason)."""
    for t in tests:
        binary = args.build / t["binary"]
        cmd = [str(binary), "--gtest_brief=1"]
        if not args.no_fail_fast:
            cmd.append("--gtest_fail_fast")
        if t.get("filter"):
            cmd.append(f"--gtest_filter={t['filter']}")
        left = deadline - time.monotonic()
        if left <= 0:
            return False, "timeout"
        rc, out = run_logged(cmd, log, left, cwd=binary.parent)
        if rc == "timeout":
            return False, f"timeout ({binary.name})"
        if rc != 0:
            failed = FAILED_RE.search(out)
            if failed:
                return False, failed.group(1)
            if rc < 0:
                return False, f"{binary.name} killed by signal {-rc}"
            return False, f"{binary.name} exit {rc}"
    return True, ""


def apply_and_test(args, guards, m, log) -> dict:
    path = ROOT / m["file"]
    original_bytes = path.read_bytes()
    text = original_bytes.decode()
    offset = locate(text, m)
    line = line_of(text, offset)
    was_clean = git_clean(path)
    mutated = text[:offset] + m["replacement"] + text[offset + len(m["original"]):]
    guard = guards[m["guard"]]
    result = {"id": m["id"], "file": m["file"], "line": line, "description": m["description"],
              "guard": m["guard"], "result": "", "killed_by": "", "seconds": 0.0,
              "equivalent": m.get("equivalent", "")}
    start = time.monotonic()
    try:
        path.write_text(mutated)
        log.write(f"== {m['id']} {m['file']}:{line}: {m['description']}\n")
        if not build(args, guard["targets"], log):
            result["result"] = "build_failed"
        else:
            passed, why = run_tests(args, guard["tests"], log, time.monotonic() + args.timeout)
            result["result"] = "survived" if passed else "killed"
            result["killed_by"] = why
    finally:
        path.write_bytes(original_bytes)
        if path.read_bytes() != original_bytes or (was_clean and not git_clean(path)):
            raise Abort(f"could not restore {path}: check it by hand (git diff)")
    result["seconds"] = round(time.monotonic() - start, 1)
    return result


def write_results(out: Path, results: list[dict], started: str, args) -> dict:
    fields = ["id", "file", "line", "description", "guard", "result", "killed_by", "seconds", "equivalent"]
    with open(out / "results.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in results:
            w.writerow({k: r.get(k, "") for k in fields})
    killed = sum(r["result"] == "killed" for r in results)
    survived = sum(r["result"] == "survived" for r in results)
    equivalent = sum(r["result"] == "survived" and bool(r["equivalent"]) for r in results)
    counted = killed + survived
    summary = {
        "started": started,
        "finished": dt.datetime.now().isoformat(timespec="seconds"),
        "commit": subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"], capture_output=True,
                                 text=True).stdout.strip(),
        "mutants_file": str(args.mutants),
        "mutants": len(results),
        "killed": killed,
        "survived": survived,
        "survived_equivalent": equivalent,
        "build_failed": sum(r["result"] == "build_failed" for r in results),
        "kill_rate": round(killed / counted, 4) if counted else None,
        "kill_rate_excluding_equivalent": round(killed / (counted - equivalent), 4) if counted > equivalent else None,
        "results": results,
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    return summary


def print_table(summary: dict) -> None:
    print("| id | where | mutation | result | killed by / why equivalent |")
    print("|---|---|---|---|---|")
    for r in summary["results"]:
        why = r["killed_by"] or r.get("equivalent", "")
        print(f"| {r['id']} | `{r['file']}:{r['line']}` | {r['description']} | {r['result']} | {why} |")
    print(f"\n{summary['killed']} killed, {summary['survived']} survived "
          f"({summary['survived_equivalent']} marked equivalent), {summary['build_failed']} did not build; "
          f"kill rate {summary['kill_rate']}, excluding equivalent {summary['kill_rate_excluding_equivalent']}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, help="results folder (created): results.csv, summary.json, logs/")
    ap.add_argument("--mutants", type=Path, default=DEFAULT_MUTANTS, help="mutant list (default: %(default)s)")
    ap.add_argument("--build", type=Path, default=DEFAULT_BUILD,
                    help="configured CMake build folder (default: %(default)s)")
    ap.add_argument("--only", nargs="+", metavar="ID", help="run only these mutants")
    ap.add_argument("--list", action="store_true", help="list the mutants and exit")
    ap.add_argument("--jobs", type=int, default=1, help="build jobs (default: %(default)s)")
    ap.add_argument("--timeout", type=float, default=300, help="seconds of tests per mutant (default: %(default)s)")
    ap.add_argument("--build-timeout", type=float, default=1800, help="seconds per build (default: %(default)s)")
    ap.add_argument("--table", type=Path, metavar="SUMMARY_JSON",
                    help="print a Markdown table of a finished run's summary.json and exit")
    ap.add_argument("--no-fail-fast", action="store_true", help="run every test even after a failure")
    ap.add_argument("--skip-baseline", action="store_true",
                    help="do not first check that the guarding tests pass without mutants")
    args = ap.parse_args()
    signal.signal(signal.SIGTERM, on_sigterm)
    if args.table:
        print_table(json.loads(args.table.read_text()))
        return 0
    try:
        guards, mutants = load_mutants(args.mutants)
        if args.only:
            unknown = set(args.only) - {m["id"] for m in mutants}
            if unknown:
                raise Abort(f"unknown mutant ids: {', '.join(sorted(unknown))}")
            mutants = [m for m in mutants if m["id"] in args.only]
        for m in mutants:  # every snippet checked before anything is touched
            locate((ROOT / m["file"]).read_text(), m)
        if args.list:
            for m in mutants:
                text = (ROOT / m["file"]).read_text()
                eq = "  [equivalent]" if m.get("equivalent") else ""
                print(f"{m['id']:5} {m['file']}:{line_of(text, locate(text, m))}  {m['description']}{eq}")
            return 0
        if args.out is None:
            ap.error("--out DIR is required (or --list)")
        args.build = args.build.resolve()
        if not (args.build / "CMakeCache.txt").exists():
            raise Abort(f"{args.build} is not a configured build folder (cmake -S {ROOT} -B {args.build} ...)")
        out = args.out.resolve()
        (out / "logs").mkdir(parents=True, exist_ok=True)
        started = dt.datetime.now().isoformat(timespec="seconds")
        if not args.skip_baseline:
            used = sorted({g for g in (m["guard"] for m in mutants)})
            print(f"baseline: building and testing guards {', '.join(used)} without mutants", flush=True)
            with open(out / "logs" / "baseline.log", "w") as log:
                for g in used:
                    if not build(args, guards[g]["targets"], log):
                        raise Abort(f"baseline build of guard {g} failed: {out / 'logs' / 'baseline.log'}")
                    ok, why = run_tests(args, guards[g]["tests"], log, time.monotonic() + args.timeout)
                    if not ok:
                        raise Abort(f"baseline tests of guard {g} fail without a mutant ({why}): fix that first")
        results = []
        for i, m in enumerate(mutants, 1):
            with open(out / "logs" / f"{m['id']}.log", "w") as log:
                r = apply_and_test(args, guards, m, log)
            results.append(r)
            extra = f" by {r['killed_by']}" if r["killed_by"] else ""
            eq = " (marked equivalent)" if r["result"] == "survived" and r["equivalent"] else ""
            print(f"[{i}/{len(mutants)}] {m['id']:5} {r['result']:12} {r['seconds']:6.1f}s  "
                  f"{m['file']}:{r['line']} {m['description']}{extra}{eq}", flush=True)
            write_results(out, results, started, args)
        s = write_results(out, results, started, args)
        # Leave the build folder matching the restored sources.
        with open(out / "logs" / "rebuild.log", "w") as log:
            for g in sorted({m["guard"] for m in mutants}):
                build(args, guards[g]["targets"], log)
        print(f"\n{s['killed']} killed, {s['survived']} survived ({s['survived_equivalent']} marked equivalent), "
              f"{s['build_failed']} did not build; kill rate {s['kill_rate']}, "
              f"excluding equivalent {s['kill_rate_excluding_equivalent']}. Results: {out}")
        return 0
    except Abort as e:
        print(f"mutate.py: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("mutate.py: interrupted (the mutated file was restored)", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
